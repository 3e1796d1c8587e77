/* strmap.c: string -> id hash map (see strmap.h). */
#include "strmap.h"

#include <stdlib.h>
#include <string.h>

uint64_t strmap_hash(const char *s, size_t n)
{
    uint64_t h = 0xcbf29ce484222325ULL; /* FNV-1a */
    for (size_t i = 0; i < n; i++)
        h = (h ^ (unsigned char)s[i]) * 0x100000001b3ULL;
    return h;
}

long strmap_find(const struct strmap *m, const struct strmap_key *keys, const char *s, size_t n,
                 uint64_t h)
{
    if (!m->e)
        return -1;
    for (size_t i = (size_t)h & m->mask; m->e[i].id1; i = (i + 1) & m->mask) {
        const struct strmap_key *k = &keys[m->e[i].id1 - 1];
        if (m->e[i].hash == h && k->n == n && memcmp(k->s, s, n) == 0)
            return (long)m->e[i].id1 - 1;
    }
    return -1;
}

static void put(struct strmap *m, uint64_t h, uint32_t id)
{
    size_t i = (size_t)h & m->mask;
    while (m->e[i].id1)
        i = (i + 1) & m->mask;
    m->e[i].hash = h;
    m->e[i].id1 = id + 1;
    m->count++;
}

int strmap_add(struct strmap *m, uint64_t h, uint32_t id)
{
    if (!m->e || (m->count + 1) * 2 > m->mask + 1) {
        size_t cap = m->e ? (m->mask + 1) * 2 : 16;
        struct strmap g = {calloc(cap, sizeof *g.e), cap - 1, 0};
        if (!g.e)
            return -1;
        for (size_t i = 0; m->e && i <= m->mask; i++)
            if (m->e[i].id1)
                put(&g, m->e[i].hash, m->e[i].id1 - 1);
        free(m->e);
        *m = g;
    }
    put(m, h, id);
    return 0;
}

void strmap_free(struct strmap *m)
{
    free(m->e);
    memset(m, 0, sizeof *m);
}
