// The ACL side of bench_codec_vs: ACL (../shared/peers/acl, header only) at
// its "medium" compression level with its default formats (variable bit
// rates), the qvvf error metric, error threshold 0.01 cm and 3 cm shell, on
// the same clips. ACL is only ever included here, in a benchmark program
// that is built when the peer folder exists; nothing of the box links it.
// Units: ACL is fed centimetres, as its published CMU figures are.
#include <acl/compression/compress.h>
#include <acl/compression/track_array.h>
#include <acl/compression/transform_error_metrics.h>
#include <acl/core/ansi_allocator.h>
#include <acl/decompression/decompress.h>

#include <chrono>
#include <cstdio>
#include <cstring>

#include "codec_vs.h"

namespace
{

// One pose as ACL writes it, per track (our bones, end sites left out).
struct pose_writer final : public acl::track_writer {
    static constexpr bool skip_all_scales() { return true; }
    float rot[CUB_MOTION_MAX_JOINTS][4];
    float pos[CUB_MOTION_MAX_JOINTS][3];
    void RTM_SIMD_CALL write_rotation(uint32_t i, rtm::quatf_arg0 q)
    {
        rot[i][0] = rtm::quat_get_w(q);
        rot[i][1] = rtm::quat_get_x(q);
        rot[i][2] = rtm::quat_get_y(q);
        rot[i][3] = rtm::quat_get_z(q);
    }
    void RTM_SIMD_CALL write_translation(uint32_t i, rtm::vector4f_arg0 t)
    {
        pos[i][0] = rtm::vector_get_x(t);
        pos[i][1] = rtm::vector_get_y(t);
        pos[i][2] = rtm::vector_get_z(t);
    }
};

struct acl_state {
    acl::ansi_allocator alloc;
    acl::compressed_tracks *tracks = nullptr;
    acl::decompression_context<acl::default_transform_decompression_settings> ctx;
    const cub_clip *clip = nullptr;
    int track_of[CUB_MOTION_MAX_JOINTS]; // joint -> ACL track, -1 for end sites
    float rate = 30.0f;
    pose_writer out;

    void drop()
    {
        if (tracks) alloc.deallocate(tracks, tracks->get_size());
        tracks = nullptr;
    }
};

acl_state state;

double q(int32_t v)
{
    return v / 1073741824.0;
}
double mm(int32_t v)
{
    return v / 65536.0;
}

// The local transform of joint j at frame f as a qvvf in centimetres.
rtm::qvvf source_transform(const cub_clip *c, int f, int j)
{
    int jn = c->skel->joint_count;
    const cub_quat &r = c->rot[(size_t)f * jn + j];
    cub_vec3 t = j == 0        ? c->root_mm[f]
                 : c->trans_mm ? c->trans_mm[(size_t)f * jn + j]
                               : c->skel->joints[j].offset_mm;
    rtm::quatf rq = rtm::quat_normalize(
        rtm::quat_set((float)q(r.x), (float)q(r.y), (float)q(r.z), (float)q(r.w)));
    rtm::vector4f tv =
        rtm::vector_set((float)(mm(t.x) / 10.0), (float)(mm(t.y) / 10.0), (float)(mm(t.z) / 10.0));
    return rtm::qvv_set(rq, tv, rtm::vector_set(1.0f));
}

int acl_encode(void *, const cub_clip *clip, size_t *bytes)
{
    acl_state &s = state;
    s.drop();
    s.clip = clip;
    s.rate = (float)(1e9 / clip->frame_ns);
    const cub_skeleton *sk = clip->skel;
    uint32_t ntracks = 0;
    for (int j = 0; j < sk->joint_count; j++)
        s.track_of[j] = sk->joints[j].is_end_site ? -1 : (int)ntracks++;
    acl::track_array_qvvf list(s.alloc, ntracks);
    for (int j = 0; j < sk->joint_count; j++) {
        if (s.track_of[j] < 0) continue;
        acl::track_desc_transformf desc;
        desc.output_index = (uint32_t)s.track_of[j];
        desc.parent_index =
            j == 0 ? acl::k_invalid_track_index : (uint32_t)s.track_of[sk->joints[j].parent];
        desc.precision = 0.01f;     // cm, ACL's default
        desc.shell_distance = 3.0f; // cm, ACL's default
        acl::track_qvvf t =
            acl::track_qvvf::make_reserve(desc, s.alloc, (uint32_t)clip->frame_count, s.rate);
        for (int f = 0; f < clip->frame_count; f++)
            t[(uint32_t)f] = source_transform(clip, f, j);
        list[(uint32_t)s.track_of[j]] = std::move(t);
    }
    acl::compression_settings settings = acl::get_default_compression_settings();
    settings.level = acl::compression_level8::medium;
    acl::qvvf_transform_error_metric metric;
    settings.error_metric = &metric;
    acl::output_stats stats;
    acl::error_result r = acl::compress_track_list(s.alloc, list, settings, s.tracks, stats);
    if (r.any()) {
        std::fprintf(stderr, "bench_codec_vs: ACL refused the clip: %s\n", r.c_str());
        s.tracks = nullptr;
        return -1;
    }
    s.ctx.initialize(*s.tracks);
    *bytes = s.tracks->get_size();
    return 0;
}

int acl_pose(void *, int frame, vs_pose *out)
{
    acl_state &s = state;
    s.ctx.seek((float)frame / s.rate, acl::sample_rounding_policy::nearest);
    s.ctx.decompress_tracks(s.out);
    const cub_skeleton *sk = s.clip->skel;
    for (int j = 0; j < sk->joint_count; j++) {
        int t = s.track_of[j];
        if (t < 0) continue;
        for (int k = 0; k < 4; k++)
            out->rot[j][k] = s.out.rot[t][k];
        for (int k = 0; k < 3; k++)
            out->pos[j][k] = s.out.pos[t][k] * 10.0;
    }
    return 0;
}

double acl_time_all(void *)
{
    acl_state &s = state;
    auto t0 = std::chrono::steady_clock::now();
    for (int f = 0; f < s.clip->frame_count; f++) {
        s.ctx.seek((float)f / s.rate, acl::sample_rounding_policy::none);
        s.ctx.decompress_tracks(s.out);
    }
    std::chrono::duration<double> d = std::chrono::steady_clock::now() - t0;
    return d.count();
}

void acl_release(void *)
{
    state.drop();
}

} // namespace

extern "C" int vs_acl_codec(vs_codec *out)
{
    *out = vs_codec{"acl", acl_encode, acl_pose, acl_time_all, acl_release, nullptr};
    return 0;
}
