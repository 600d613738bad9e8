/* The packed state store: fixed-width records in one arena, an open-addressing hash table over it.
 *
 * A state is a record of `nf` unsigned fields; field f is w[f] bytes wide (1, 2, 4 or 8, little-endian
 * as the caller packs it). Record i lives at arena + i * W. The table holds id + 1 per slot (0: empty),
 * linear probing, at most three quarters full; it is rebuilt from the arena when it grows or the widths change.
 * Below 2^24 - 1 records a slot keeps the top 8 bits of the record's hash above its 24-bit id + 1, so that
 * a probe compares a record (a likely cache miss in the arena) only when those bits agree.
 * Records known to be distinct can be appended without the table (cs_append: the threads' graph is put
 * together so); the table is then built when a record is first looked up or added.
 */
#include "_packed.h"

int cs_rehash(cs_store *s, uint64_t size) {
    uint32_t *t = (uint32_t *)calloc(size, sizeof(uint32_t));
    if (!t) return -1;
    uint64_t mask = size - 1;
    s->tagged = s->n < CS_TAG_LIMIT;
    /* the records' slots are random places of a table larger than the caches: each is prefetched
     * CS_AHEAD records before it is written */
    enum { CS_AHEAD = 16 };
    uint64_t ring[CS_AHEAD];
    for (int64_t i = 0; i < s->n + CS_AHEAD; i++) {
        if (i >= CS_AHEAD) {
            int64_t j = i - CS_AHEAD;
            uint64_t hh = ring[j % CS_AHEAD], h = hh & mask;
            while (t[h]) h = (h + 1) & mask;
            t[h] = cs_slot(s, j, hh);
        }
        if (i < s->n) {
            uint64_t hh = cs_hash(s->arena + i * s->W, s->W);
            ring[i % CS_AHEAD] = hh;
            __builtin_prefetch(t + (hh & mask), 1);
        }
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
    s->off = (int *)malloc(sizeof(int) * (size_t)(nf > 0 ? nf : 1));
    if (!s->w || !s->off) return NULL;
    s->W = 0;
    for (int f = 0; f < nf; f++) { s->w[f] = w[f]; s->off[f] = s->W; s->W += w[f]; }
    s->cap = 1024;
    s->arena = (uint8_t *)malloc((size_t)(s->cap * (s->W ? s->W : 1)));
    if (!s->w || !s->arena || cs_rehash(s, 2048) != 0) return NULL;
    return s;
}

void cs_free(cs_store *s) {
    if (!s) return;
    free(s->w); free(s->off); free(s->arena); free(s->table); free(s);
}

/* Build the table of a store whose records were appended without it: 0, or -1 without memory. */
int cs_index(cs_store *s) {
    uint64_t size = 2048;
    while ((uint64_t)s->n * 4 > size * 3) size *= 2;  /* as cs_add_hashed grows it: at most 3/4 full */
    if (cs_rehash(s, size) != 0) return -1;
    s->unindexed = 0;
    return 0;
}

/* The id of record r, -1 if it is not stored (-2 without memory for the table). */
int64_t cs_find(cs_store *s, const uint8_t *r) {
    uint64_t slot;
    if (s->unindexed && cs_index(s) != 0) return -2;
    return cs_lookup(s, r, cs_hash(r, s->W), &slot);
}

/* Insert n records (packed one after the other); ids[k] receives record k's id. The positions k of the
 * records that were new are written to fresh[], in order; returns how many there were, or -1 when
 * memory ran out (then nothing of this batch past the failing record was stored). */
int64_t cs_add_many(cs_store *s, const uint8_t *recs, int64_t n, int32_t *ids, int32_t *fresh) {
    int64_t nfresh = 0;
    int W = s->W;
    for (int64_t k = 0; k < n; k++) {
        const uint8_t *r = recs + k * W;
        int rc = cs_add_hashed(s, r, cs_hash(r, W), ids + k);
        if (rc < 0) return -1;
        if (rc) fresh[nfresh++] = (int32_t)k;
    }
    return nfresh;
}

/* Empty the store (its records are to be appended again). */
void cs_clear(cs_store *s) {
    s->n = 0;
    s->unindexed = 1;
}

/* Append n records known to be distinct (from each other and from those stored) without the table;
 * 0, or -1 without memory. */
int cs_append(cs_store *s, const uint8_t *recs, int64_t n) {
    int W = s->W;
    if (s->n + n > 0x7FFFFFFE) return -1;
    if (s->n + n > s->cap) {
        int64_t cap = s->cap;
        while (cap < s->n + n) cap *= 2;
        uint8_t *a = (uint8_t *)realloc(s->arena, (size_t)(cap * (W ? W : 1)));
        if (!a) return -1;
        s->arena = a; s->cap = cap;
    }
    memcpy(s->arena + s->n * W, recs, (size_t)(n * W));
    s->n += n;
    s->unindexed = 1;
    return 0;
}

/* Make field f at least w bytes wide (the records re-laid, the table rebuilt); 0, or -1 without memory. */
int cs_widen_field(cs_store *s, int f, int w) {
    if (s->w[f] >= w) return 0;
    uint8_t *ws = (uint8_t *)malloc((size_t)s->nf);
    if (!ws) return -1;
    memcpy(ws, s->w, (size_t)s->nf);
    ws[f] = (uint8_t)w;
    int rc = cs_widen(s, ws);
    free(ws);
    return rc;
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
    for (int f = 0, o = 0; f < s->nf; f++) { s->off[f] = o; o += w[f]; }
    return s->unindexed ? 0 : cs_rehash(s, s->mask + 1);
}

int64_t cs_count(cs_store *s) { return s->n; }
int cs_width(cs_store *s) { return s->W; }
const uint8_t *cs_widths(cs_store *s) { return s->w; }
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
