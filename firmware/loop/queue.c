/* The event queue: a power-of-two ring buffer over caller memory. head and
 * tail run freely and wrap through uint32 arithmetic, so count = tail - head
 * needs no special "full" flag. */
#include "cub/loop.h"

cub_err cub_queue_init(cub_queue *q, cub_event *slots, uint32_t capacity)
{
    if (!q || !slots || capacity < 2 || (capacity & (capacity - 1)) != 0) return CUB_ERR_ARG;
    q->slots = slots;
    q->capacity = capacity;
    q->head = q->tail = 0;
    q->dropped = 0;
    return CUB_OK;
}

uint32_t cub_queue_count(const cub_queue *q)
{
    return q->tail - q->head;
}

cub_err cub_queue_push(cub_queue *q, const cub_event *ev)
{
    if (!ev) return CUB_ERR_ARG;
    if (cub_queue_count(q) >= q->capacity) {
        q->dropped++;
        return CUB_ERR_FULL;
    }
    q->slots[q->tail & (q->capacity - 1)] = *ev;
    q->tail++;
    return CUB_OK;
}

cub_err cub_queue_pop(cub_queue *q, cub_event *out)
{
    if (cub_queue_count(q) == 0) return CUB_ERR_EMPTY;
    if (out) *out = q->slots[q->head & (q->capacity - 1)];
    q->head++;
    return CUB_OK;
}
