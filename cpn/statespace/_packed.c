/* The packed state store: fixed-width records in one arena, an open-addressing hash table over it.
 *
 * A state is a record of `nf` unsigned fields; field f is w[f] bytes wide (1, 2, 4 or 8, little-endian
 * as the caller packs it). Record i lives at arena + i * W. The table holds id + 1 per slot (0: empty),
 * linear probing, at most three quarters full; it is rebuilt from the arena when it grows or the widths change.
 * Below 2^24 - 1 records a slot keeps the top 8 bits of the record's hash above its 24-bit id + 1, so that
 * a probe compares a record (a likely cache miss in the arena) only when those bits agree.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    int nf;
    int W;
    uint8_t *w;
    uint8_t *arena;
    int64_t n, cap;
    uint32_t *table;
    uint64_t mask;
    int tagged;              /* slots carry 8 bits of hash (fewer than CS_TAG_LIMIT records) */
} cs_store;

#define CS_TAG_LIMIT ((int64_t)0xFFFFFE)

static inline uint32_t cs_slot(const cs_store *s, int64_t id, uint64_t h) {
    return s->tagged ? (uint32_t)(id + 1) | ((uint32_t)(h >> 56) << 24) : (uint32_t)(id + 1);
}

static uint64_t cs_hash(const uint8_t *r, int W) {
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

static int cs_rehash(cs_store *s, uint64_t size) {
    uint32_t *t = (uint32_t *)calloc(size, sizeof(uint32_t));
    if (!t) return -1;
    uint64_t mask = size - 1;
    s->tagged = s->n < CS_TAG_LIMIT;
    for (int64_t i = 0; i < s->n; i++) {
        uint64_t hh = cs_hash(s->arena + i * s->W, s->W), h = hh & mask;
        while (t[h]) h = (h + 1) & mask;
        t[h] = cs_slot(s, i, hh);
    }
    free(s->table);
    s->table = t;
    s->mask = mask;
    return 0;
}

cs_store *cs_new(int nf, const uint8_t *w) {
    cs_store *s = (cs_store *)calloc(1, sizeof(cs_store));
    if (!s) return NULL;
    s->nf = nf;
    s->w = (uint8_t *)malloc(nf > 0 ? (size_t)nf : 1);
    s->W = 0;
    for (int f = 0; f < nf; f++) { s->w[f] = w[f]; s->W += w[f]; }
    s->cap = 1024;
    s->arena = (uint8_t *)malloc((size_t)(s->cap * (s->W ? s->W : 1)));
    if (!s->w || !s->arena || cs_rehash(s, 2048) != 0) return NULL;
    return s;
}

void cs_free(cs_store *s) {
    if (!s) return;
    free(s->w); free(s->arena); free(s->table); free(s);
}

static int64_t cs_lookup(cs_store *s, const uint8_t *r, uint64_t *slot, uint64_t *hash) {
    uint64_t hh = cs_hash(r, s->W), h = hh & s->mask;
    int W = s->W;
    *hash = hh;
    if (s->tagged) {
        uint32_t tag = (uint32_t)(hh >> 56);
        for (;;) {
            uint32_t e = s->table[h];
            if (!e) { *slot = h; return -1; }
            if ((e >> 24) == tag) {
                int64_t id = (int64_t)(e & 0xFFFFFF) - 1;
                if (memcmp(s->arena + id * W, r, (size_t)W) == 0) return id;
            }
            h = (h + 1) & s->mask;
        }
    }
    for (;;) {
        uint32_t e = s->table[h];
        if (!e) { *slot = h; return -1; }
        if (memcmp(s->arena + (int64_t)(e - 1) * W, r, (size_t)W) == 0) return (int64_t)e - 1;
        h = (h + 1) & s->mask;
    }
}

int64_t cs_find(cs_store *s, const uint8_t *r) {
    uint64_t slot, hash;
    return cs_lookup(s, r, &slot, &hash);
}

/* Insert n records (packed one after the other); ids[k] receives record k's id. The positions k of the
 * records that were new are written to fresh[], in order; returns how many there were, or -1 when
 * memory ran out (then nothing of this batch past the failing record was stored). */
int64_t cs_add_many(cs_store *s, const uint8_t *recs, int64_t n, int32_t *ids, int32_t *fresh) {
    int64_t nfresh = 0;
    int W = s->W;
    for (int64_t k = 0; k < n; k++) {
        const uint8_t *r = recs + k * W;
        uint64_t slot, hash;
        int64_t id = cs_lookup(s, r, &slot, &hash);
        if (id < 0) {
            if (s->n >= 0x7FFFFFFE) return -1;
            if (s->n == s->cap) {
                int64_t cap = s->cap * 2;
                uint8_t *a = (uint8_t *)realloc(s->arena, (size_t)(cap * (W ? W : 1)));
                if (!a) return -1;
                s->arena = a; s->cap = cap;
            }
            memcpy(s->arena + s->n * W, r, (size_t)W);
            id = s->n++;
            s->table[slot] = cs_slot(s, id, hash);
            if (s->tagged && s->n >= CS_TAG_LIMIT) {  /* ids outgrow 24 bits: plain slots from now on */
                if (cs_rehash(s, s->mask + 1) != 0) return -1;
            }
            if ((uint64_t)s->n * 4 > (s->mask + 1) * 3) {
                if (cs_rehash(s, (s->mask + 1) * 2) != 0) return -1;
            }
            fresh[nfresh++] = (int32_t)k;
        }
        ids[k] = (int32_t)id;
    }
    return nfresh;
}

/* Re-lay every record with the new widths (each at least the old one) and rebuild the table. */
int cs_widen(cs_store *s, const uint8_t *w) {
    int W2 = 0;
    for (int f = 0; f < s->nf; f++) W2 += w[f];
    uint8_t *a = (uint8_t *)malloc((size_t)(s->cap * (W2 ? W2 : 1)));
    if (!a) return -1;
    for (int64_t i = 0; i < s->n; i++) {
        const uint8_t *src = s->arena + i * s->W;
        uint8_t *dst = a + i * W2;
        for (int f = 0; f < s->nf; f++) {
            memset(dst, 0, w[f]);
            memcpy(dst, src, s->w[f]);  /* little-endian: the low bytes first */
            src += s->w[f];
            dst += w[f];
        }
    }
    free(s->arena);
    s->arena = a;
    s->W = W2;
    memcpy(s->w, w, (size_t)s->nf);
    return cs_rehash(s, s->mask + 1);
}

int64_t cs_count(cs_store *s) { return s->n; }
int cs_width(cs_store *s) { return s->W; }
const uint8_t *cs_arena(cs_store *s) { return s->arena; }
int64_t cs_nbytes(cs_store *s) {
    return (int64_t)sizeof(cs_store) + s->nf + s->cap * s->W + (int64_t)(s->mask + 1) * 4;
}

/* Give back the arena's unused tail once the search is over. */
void cs_trim(cs_store *s) {
    if (s->n == 0 || s->n == s->cap) return;
    uint8_t *a = (uint8_t *)realloc(s->arena, (size_t)(s->n * (s->W ? s->W : 1)));
    if (a) { s->arena = a; s->cap = s->n; }
}
