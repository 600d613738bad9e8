/* The packed state store (_packed.c): what Python calls (between the cffi markers) and what the searches
 * (_search.c, _timed.c, _threads.c) use of it: the record layout and the inline record helpers of their
 * inner loops. */
#ifndef CPN_PACKED_H
#define CPN_PACKED_H

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* cffi: begin */
typedef struct cs_store cs_store;
cs_store *cs_new(int nf, const uint8_t *w);
void cs_free(cs_store *s);
int64_t cs_find(cs_store *s, const uint8_t *r);
int64_t cs_add_many(cs_store *s, const uint8_t *recs, int64_t n, int32_t *ids, int32_t *fresh);
int cs_widen(cs_store *s, const uint8_t *w);
int64_t cs_count(cs_store *s);
int cs_width(cs_store *s);
const uint8_t *cs_widths(cs_store *s);
const uint8_t *cs_arena(cs_store *s);
int64_t cs_nbytes(cs_store *s);
void cs_trim(cs_store *s);
/* cffi: end */

struct cs_store {
    int nf;
    int W;
    uint8_t *w;
    int *off;                /* byte offset of each field in a record */
    uint8_t *arena;
    int64_t n, cap;
    uint32_t *table;
    uint64_t mask;
    int tagged;              /* slots carry 8 bits of hash (fewer than CS_TAG_LIMIT records) */
    int unindexed;           /* the table is not built (cs_append) */
};

#define CS_TAG_LIMIT ((int64_t)0xFFFFFE)

int cs_rehash(cs_store *s, uint64_t size);
int cs_index(cs_store *s);
int cs_widen_field(cs_store *s, int f, int w);
void cs_clear(cs_store *s);
int cs_append(cs_store *s, const uint8_t *recs, int64_t n);

/* A field's value in a record, and the record with a field set (0: the value does not fit its width). */
static inline uint64_t cs_get(const uint8_t *r, int w) {
    switch (w) {
    case 1: return r[0];
    case 2: return (uint64_t)r[0] | (uint64_t)r[1] << 8;
    case 4: return (uint64_t)r[0] | (uint64_t)r[1] << 8 | (uint64_t)r[2] << 16 | (uint64_t)r[3] << 24;
    default: { uint64_t v = 0; for (int i = w - 1; i >= 0; i--) v = v << 8 | r[i]; return v; }
    }
}

static inline int cs_put(uint8_t *r, int w, uint64_t v) {
    switch (w) {
    case 1: if (v > 0xFFu) return 0; r[0] = (uint8_t)v; return 1;
    case 2: if (v > 0xFFFFu) return 0; r[0] = (uint8_t)v; r[1] = (uint8_t)(v >> 8); return 1;
    case 4:
        if (v > 0xFFFFFFFFu) return 0;
        r[0] = (uint8_t)v; r[1] = (uint8_t)(v >> 8); r[2] = (uint8_t)(v >> 16); r[3] = (uint8_t)(v >> 24);
        return 1;
    default: for (int i = 0; i < w; i++) { r[i] = (uint8_t)v; v >>= 8; } return 1;
    }
}

static inline uint32_t cs_slot(const cs_store *s, int64_t id, uint64_t h) {
    return s->tagged ? (uint32_t)(id + 1) | ((uint32_t)(h >> 56) << 24) : (uint32_t)(id + 1);
}

static inline uint64_t cs_hash(const uint8_t *r, int W) {
    uint64_t h = 0x9E3779B97F4A7C15ULL ^ (uint64_t)W;
    int i = 0;
    for (; i + 8 <= W; i += 8) {
        uint64_t x;
        memcpy(&x, r + i, 8);
        h = (h ^ x) * 0xBF58476D1CE4E5B9ULL;
        h ^= h >> 31;
    }
    if (i < W) {
        uint64_t x = 0;
        memcpy(&x, r + i, (size_t)(W - i));
        h = (h ^ x) * 0xBF58476D1CE4E5B9ULL;
        h ^= h >> 31;
    }
    h *= 0x94D049BB133111EBULL;
    return h ^ (h >> 29);
}

static inline int cs_same(const uint8_t *a, const uint8_t *b, int W) {
    int i = 0;
    for (; i + 8 <= W; i += 8) {
        uint64_t x, y;
        memcpy(&x, a + i, 8);
        memcpy(&y, b + i, 8);
        if (x != y) return 0;
    }
    for (; i < W; i++) if (a[i] != b[i]) return 0;
    return 1;
}

/* The id of record r whose hash is hh, or -1 with the empty slot where it would go. */
static inline int64_t cs_lookup(const cs_store *s, const uint8_t *r, uint64_t hh, uint64_t *slot) {
    uint64_t h = hh & s->mask;
    int W = s->W;
    if (s->tagged) {
        uint32_t tag = (uint32_t)(hh >> 56);
        for (;;) {
            uint32_t e = s->table[h];
            if (!e) { *slot = h; return -1; }
            if ((e >> 24) == tag) {
                int64_t id = (int64_t)(e & 0xFFFFFF) - 1;
                if (cs_same(s->arena + id * W, r, W)) return id;
            }
            h = (h + 1) & s->mask;
        }
    }
    for (;;) {
        uint32_t e = s->table[h];
        if (!e) { *slot = h; return -1; }
        if (cs_same(s->arena + (int64_t)(e - 1) * W, r, W)) return (int64_t)e - 1;
        h = (h + 1) & s->mask;
    }
}

/* Where a record of hash hh is looked for first (for a prefetch). */
static inline const uint32_t *cs_probe_start(const cs_store *s, uint64_t hh) { return s->table + (hh & s->mask); }

/* Store record r of hash hh if it is new: its id in *id; 1 if it was new, 0 if not, -1 when memory ran out. */
static inline int cs_add_hashed(cs_store *s, const uint8_t *r, uint64_t hh, int32_t *id) {
    uint64_t slot;
    if (s->unindexed && cs_index(s) != 0) return -1;
    int64_t i = cs_lookup(s, r, hh, &slot);
    if (i >= 0) { *id = (int32_t)i; return 0; }
    int W = s->W;
    if (s->n >= 0x7FFFFFFE) return -1;
    if (s->n == s->cap) {
        int64_t cap = s->cap * 2;
        uint8_t *a = (uint8_t *)realloc(s->arena, (size_t)(cap * (W ? W : 1)));
        if (!a) return -1;
        s->arena = a; s->cap = cap;
    }
    memcpy(s->arena + s->n * W, r, (size_t)W);
    i = s->n++;
    s->table[slot] = cs_slot(s, i, hh);
    if (s->tagged && s->n >= CS_TAG_LIMIT) {  /* ids outgrow 24 bits: plain slots from now on */
        if (cs_rehash(s, s->mask + 1) != 0) return -1;
    }
    if ((uint64_t)s->n * 4 > (s->mask + 1) * 3) {
        if (cs_rehash(s, (s->mask + 1) * 2) != 0) return -1;
    }
    *id = (int32_t)i;
    return 1;
}

#endif
