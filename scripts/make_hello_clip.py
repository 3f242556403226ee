#!/usr/bin/env python3
"""Write assets/clips/hello.bvh: the stick-figure coach's first clip.

A hand-keyed wave authored by the project (no third-party motion capture):
a 24-joint humanoid in centimetres, facing +z with y up, 8 keys at four per
second. The firmware's sampler interpolates between the keys, and when it
loops a clip it blends the last key back into the first, so the keys are
one period of the motion with no closing repeat.
Run from the repository root: python3 scripts/make_hello_clip.py
"""
import math

KEYS = 8
FRAME_TIME = 0.25


def skeleton():
    joints = []  # (name, parent, offset_cm, channel count)

    def joint(name, parent, off, ch=3):
        joints.append((name, parent, off, ch))

    joint("Hips", None, (0, 0, 0), 6)
    joint("Spine", "Hips", (0, 12, 0))
    joint("Chest", "Spine", (0, 14, 0))
    joint("Neck", "Chest", (0, 16, 0))
    joint("Head", "Neck", (0, 8, 0))
    joint("Head_end", "Head", (0, 14, 0), 0)
    for side, sx in (("Left", 1), ("Right", -1)):
        joint(side + "Shoulder", "Chest", (sx * 4, 14, 0))
        joint(side + "Arm", side + "Shoulder", (sx * 14, 0, 0))
        joint(side + "ForeArm", side + "Arm", (sx * 28, 0, 0))
        joint(side + "Hand", side + "ForeArm", (sx * 25, 0, 0))
        joint(side + "Hand_end", side + "Hand", (sx * 8, 0, 0), 0)
    for side, sx in (("Left", 1), ("Right", -1)):
        joint(side + "UpLeg", "Hips", (sx * 9, 0, 0))
        joint(side + "Leg", side + "UpLeg", (0, -44, 0))
        joint(side + "Foot", side + "Leg", (0, -42, 0))
        joint(side + "Foot_end", side + "Foot", (0, -8, 12), 0)
    return joints


def hierarchy(joints):
    children = {}
    for j in joints:
        children.setdefault(j[1], []).append(j)
    out = ["HIERARCHY"]

    def emit(j, depth):
        name, parent, off, ch = j
        ind = "  " * depth
        offset = f"OFFSET {off[0]:.2f} {off[1]:.2f} {off[2]:.2f}"
        if ch == 0:
            out.extend([f"{ind}End Site", ind + "{", f"{ind}  {offset}", ind + "}"])
            return
        out.extend([f"{ind}{'ROOT' if parent is None else 'JOINT'} {name}", ind + "{",
                    f"{ind}  {offset}"])
        if ch == 6:
            out.append(f"{ind}  CHANNELS 6 Xposition Yposition Zposition "
                       "Zrotation Xrotation Yrotation")
        else:
            out.append(f"{ind}  CHANNELS 3 Zrotation Xrotation Yrotation")
        for c in children.get(name, []):
            emit(c, depth + 1)
        out.append(ind + "}")

    emit(joints[0], 0)
    return out


def key(k, moving):
    """Degrees (Z, X, Y) per joint at key k. Rotations about z swing a limb in
    the picture plane: the right arm (along -x) goes up and out at -60."""
    ph = 2 * math.pi * k / KEYS
    rot = {name: [0.0, 0.0, 0.0] for name in moving}
    rot["RightArm"][0] = -60 + 8 * math.sin(ph)     # raised up and out
    rot["RightForeArm"][0] = 25 * math.sin(2 * ph)  # the wave
    rot["RightHand"][0] = 15 * math.sin(2 * ph + 0.8)
    rot["LeftArm"][0] = -70 + 5 * math.sin(ph)      # resting, a little out
    rot["LeftForeArm"][0] = -15
    rot["Spine"][0] = 4 * math.sin(ph)              # sway
    rot["Head"][0] = -6 * math.sin(ph)
    rot["LeftUpLeg"][0] = rot["RightUpLeg"][0] = 3 * math.sin(ph)
    hips_y = 94 - 1.5 * (1 - math.cos(2 * ph)) / 2  # a small bounce, cm
    values = [0.0, hips_y, 0.0]
    for name in moving:
        values += rot[name]
    return " ".join(f"{v + 0.0:.4f}" for v in values)


def main():
    joints = skeleton()
    moving = [j[0] for j in joints if j[3]]
    lines = hierarchy(joints)
    lines += ["MOTION", f"Frames: {KEYS}", f"Frame Time: {FRAME_TIME:.6f}"]
    lines += [key(k, moving).replace("-0.0000", "0.0000") for k in range(KEYS)]
    with open("assets/clips/hello.bvh", "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
