/* The native breadth-first search (_search.c): what Python calls (between the cffi markers), and what the
 * searches built on it (_timed.c, _threads.c) and the C generated from a net (cpn/engine/ccodegen.py,
 * after _cnet.c) use of it: its state, its status codes, its map and the growing of its buffers. */
#ifndef CPN_SEARCH_H
#define CPN_SEARCH_H

#include "_packed.h"

/* cffi: begin */
typedef struct nd_search nd_search;
nd_search *nd_new(cs_store *st, int K, int G, const int32_t *nread, const int32_t *nwrite, const int32_t *fields);
void nd_free(nd_search *d);
int nd_put_group(nd_search *d, int g, const uint32_t *key, int64_t n, const int32_t *entries);
int nd_put_add(nd_search *d, uint32_t p, uint32_t delta, uint32_t old, uint32_t nid);
int nd_run(nd_search *d, int64_t until, int64_t max_states, int64_t max_arcs);
void nd_clear_batch(nd_search *d);
void nd_set_be32(nd_search *d);
void nd_set_gen(nd_search *d, void *g);
void nd_set_uncache_after(nd_search *d, int64_t n);
void nd_resume(nd_search *d, int64_t head, int64_t level_end, int64_t levels, int64_t total_arcs, int be32);
int64_t nd_head(nd_search *d);
int64_t nd_levels(nd_search *d);
int64_t nd_level_end(nd_search *d);
int64_t nd_total_arcs(nd_search *d);
int64_t nd_narcs(nd_search *d);
int64_t nd_noff(nd_search *d);
int64_t nd_nnew(nd_search *d);
int32_t *nd_dst(nd_search *d);
void *nd_bes(nd_search *d);
int64_t *nd_offsets(nd_search *d);
int32_t *nd_parent(nd_search *d);
int32_t *nd_parent_be(nd_search *d);
int64_t nd_nrequests(nd_search *d);
uint32_t *nd_requests(nd_search *d);
int64_t nd_cache_bytes(nd_search *d);
int nd_uncached(nd_search *d);
/* cffi: end */

/* ---------------------------------------------------------------- a map: uint32[len] -> int64 */
typedef struct {
    int len;
    uint32_t *keys;
    int64_t *vals;
    int64_t n, cap;
    uint32_t *table;
    uint64_t mask;
} vmap;

static inline uint64_t vm_hash(const uint32_t *k, int len) {
    uint64_t h = 0x9E3779B97F4A7C15ULL ^ (uint64_t)len;
    for (int i = 0; i < len; i++) {
        h = (h ^ k[i]) * 0xBF58476D1CE4E5B9ULL;
        h ^= h >> 29;
    }
    return h ^ (h >> 32);
}

static inline int vm_same(const uint32_t *a, const uint32_t *b, int len) {
    for (int i = 0; i < len; i++) if (a[i] != b[i]) return 0;
    return 1;
}

static inline int vm_init(vmap *m, int len) {
    m->len = len; m->n = 0; m->cap = 16;
    m->keys = (uint32_t *)malloc((size_t)(m->cap * (len ? len : 1)) * 4);
    m->vals = (int64_t *)malloc((size_t)m->cap * 8);
    m->table = (uint32_t *)calloc(32, 4);
    m->mask = 31;
    return (m->keys && m->vals && m->table) ? 0 : -1;
}

static inline void vm_free(vmap *m) { free(m->keys); free(m->vals); free(m->table); }

static inline int64_t vm_get(const vmap *m, const uint32_t *k) {
    uint64_t h = vm_hash(k, m->len) & m->mask;
    for (;;) {
        uint32_t e = m->table[h];
        if (!e) return -1;
        if (vm_same(m->keys + (int64_t)(e - 1) * m->len, k, m->len)) return m->vals[e - 1];
        h = (h + 1) & m->mask;
    }
}

static inline int vm_put(vmap *m, const uint32_t *k, int64_t v) {
    if (m->n == m->cap) {
        int64_t cap = m->cap * 2;
        uint32_t *keys = (uint32_t *)realloc(m->keys, (size_t)(cap * (m->len ? m->len : 1)) * 4);
        if (!keys) return -1;
        m->keys = keys;
        int64_t *vals = (int64_t *)realloc(m->vals, (size_t)cap * 8);
        if (!vals) return -1;
        m->vals = vals; m->cap = cap;
    }
    if ((uint64_t)(m->n + 1) * 4 > (m->mask + 1) * 3) {
        uint64_t size = (m->mask + 1) * 2;
        uint32_t *t = (uint32_t *)calloc(size, 4);
        if (!t) return -1;
        for (int64_t i = 0; i < m->n; i++) {
            uint64_t h = vm_hash(m->keys + i * m->len, m->len) & (size - 1);
            while (t[h]) h = (h + 1) & (size - 1);
            t[h] = (uint32_t)(i + 1);
        }
        free(m->table); m->table = t; m->mask = size - 1;
    }
    uint64_t h = vm_hash(k, m->len) & m->mask;
    while (m->table[h]) h = (h + 1) & m->mask;
    memcpy(m->keys + m->n * m->len, k, (size_t)m->len * 4);
    m->vals[m->n] = v;
    m->table[h] = (uint32_t)(++m->n);
    return 0;
}

/* ---------------------------------------------------------------- the search */
enum { ND_DONE = 0, ND_CHECK = 1, ND_MAX_STATES = 2, ND_MAX_ARCS = 3, ND_NEED = 4, ND_WIDE_BE = 6,
       ND_NO_MEMORY = -1 };

struct nd_search {
    int K, G;
    cs_store *st;
    int *nread, *nwrite;
    int **read, **write;
    vmap *groups;            /* per group: read values -> offset into res */
    int32_t *res; int64_t nres, res_cap;  /* per cached key: [count, count x (be, reads..., deltas...)] */
    vmap adds;               /* (p, delta, old) -> new */
    int64_t head, level_end, levels, total_arcs;
    int be32;
    /* batch buffers */
    int32_t *dst; void *bes; int64_t narcs, arcs_cap, bes_cap;
    int64_t *offsets; int64_t noff, off_cap;
    int32_t *parent, *parent_be; int64_t nnew, new_cap, pbe_cap;
    /* the request */
    uint32_t *req; int64_t nreq, req_cap;
    uint32_t *req_key, *s, *t;
    uint32_t *addv; int64_t addv_cap;  /* the written fields' new values found in phase 1, in order */
    uint8_t *rs;             /* the record of the state being expanded (K x 4 bytes of room) */
    uint8_t *recs; int64_t recs_cap;   /* its successors' records, one after the other */
    uint64_t *hs; int64_t hs_cap;      /* and their hashes */
    /* Uncached results (with the generated C only): a group whose results are rarely reused (more than
     * half of its first `uncache_after` lookups missed: DP's transitions see new markings in nearly every
     * state) has them computed anew for each state into `tmp` instead of being stored; the same for the
     * written places' new ids. The generated C gives the same ids for the same key every time. */
    int32_t *tmp; int64_t ntmp, tmp_cap;
    int scratch;             /* nd_put_group writes to tmp (set around gen_group for an uncached group) */
    int64_t last_off;        /* where nd_put_group put (or found) the last result */
    uint8_t *uncached, *in_tmp;        /* per group: uncached; its result for this state is in tmp */
    int64_t *looks, *misses;           /* per group: cache lookups, and misses, while they are counted */
    uint8_t adds_uncached; int64_t adds_looks, adds_misses;
    int64_t uncache_after;
    void *gen;               /* the C generated from the net's inscriptions, if any (ND_GENERATED) */
};

#ifdef ND_GENERATED
/* compiled after this file (cpn/engine/ccodegen.py): a group's result or a written place's new id
 * computed in C; -1: left to the caller (Python), -2: no memory */
static int gen_group(void *g, nd_search *d, int k, const uint32_t *key);
static int64_t gen_add(void *g, uint32_t p, uint32_t did, uint32_t old);
#endif

/* Count a look-up in a cache (a miss if `missed`) while its hit rate is judged (*looks >= 0): once
 * `after` look-ups were counted, more than half of them misses makes it compute its results anew
 * (*uncached); the judging then ends (*looks = -1). */
static inline void nd_judge(int64_t *looks, int64_t *misses, uint8_t *uncached, int64_t after, int missed) {
    if (*looks < 0) return;
    ++*looks;
    *misses += missed;
    if (*looks == after) {
        if (2 * *misses > *looks) *uncached = 1;
        *looks = -1;
    }
}

static inline int grow(void **buf, int64_t *cap, int64_t need, size_t size) {
    if (need <= *cap) return 0;
    int64_t c = *cap;
    while (c < need) c *= 2;
    void *b = realloc(*buf, (size_t)c * size);
    if (!b) return -1;
    *buf = b; *cap = c;
    return 0;
}

#endif
