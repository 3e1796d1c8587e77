/* strmap.h: a small string -> id hash map (open addressing, linear probing, FNV-1a).
 *
 * The map stores hashes and ids only; the strings stay in the caller's key array
 * (keys[id]), so names can point into a file's text without copies. Used for OBJ usemtl
 * names, MTL material names and texture paths. Load factor kept at most 1/2. */
#ifndef RASTTY_STRMAP_H
#define RASTTY_STRMAP_H

#include <stddef.h>
#include <stdint.h>

struct strmap_key {
    const char *s;
    size_t n;
};

struct strmap {
    struct strmap_entry {
        uint64_t hash;
        uint32_t id1; /* id + 1; 0 = empty */
    } *e;
    size_t mask, count;
};

uint64_t strmap_hash(const char *s, size_t n);
/* id of the key equal to (s, n) with hash h, or -1 */
long strmap_find(const struct strmap *m, const struct strmap_key *keys, const char *s, size_t n,
                 uint64_t h);
/* Add id (the caller checked it is absent). 0, or -1 out of memory. */
int strmap_add(struct strmap *m, uint64_t h, uint32_t id);
void strmap_free(struct strmap *m);

#endif
