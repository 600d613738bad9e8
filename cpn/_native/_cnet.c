/* The run-time of the C generated from a net's inscriptions (cpn/engine/ccodegen.py): interned place
 * markings, deltas and binding elements in native memory, numbered exactly as the compiled Python engine
 * numbers them (cpn/engine/compiled.py), so that both give the same states and binding elements.
 *
 * A multiset is a list of (colour id, count) pairs in the order its colours were first added: the order of
 * the Python dict the engine builds, which is the order its tokens (and so the bindings found in it) are
 * enumerated in. Two lists with the same pairs in any order are the same multiset: the table finds it by
 * an order-independent hash and keeps the order of the first list it was given.
 *
 * Threads (ND_THREADS, the multi-threaded search of _threads.c): each thread has a context of its own
 * (gen_clone: its scratch buffers, its error flag) over the one set of tables (gtab), which is then
 * `shared`. A table is changed under its own lock (a spin lock: each place's markings, each place's
 * deltas, the binding elements with their recipes); what is read without a lock (a multiset's pairs, a
 * binding element's recipe, and a table's slots when a multiset already there is looked for: ms_find)
 * is never moved while shared: an array that grows is copied, the new one
 * published with a release store, the old one kept until gen_unshare. An entry is written before its id
 * is published, and an id reaches another thread only through a lock, a barrier or an acquire load, so
 * a reader sees the entry of any id it holds. The ids are then numbered in the order the threads reach
 * the locks: the same multisets and binding elements, numbered differently from run to run.
 */

#include "_cnet.h"

#ifdef ND_THREADS
#include <sched.h>
static void g_lock(int *l) {
    if (!__atomic_exchange_n(l, 1, __ATOMIC_ACQUIRE)) return;
    for (int spins = 0;;) {
        while (__atomic_load_n(l, __ATOMIC_RELAXED)) {
            if (++spins > 200) { spins = 0; sched_yield(); }  /* the holder may have lost its core */
#if defined(__x86_64__) || defined(__i386__)
            else __builtin_ia32_pause();
#endif
        }
        if (!__atomic_exchange_n(l, 1, __ATOMIC_ACQUIRE)) return;
    }
}
static void g_unlock(int *l) { __atomic_store_n(l, 0, __ATOMIC_RELEASE); }
#else
static void g_lock(int *l) { (void)l; }
static void g_unlock(int *l) { (void)l; }
#endif

/* Arrays replaced while the tables are shared, freed by g_keep_free. */
typedef struct { void **v; int64_t n, cap; } g_kept;

static int g_keep(g_kept *k, void *p) {
    if (k->n == k->cap) {
        int64_t cap = k->cap ? 2 * k->cap : 16;
        void **v = (void **)realloc(k->v, sizeof(void *) * (size_t)cap);
        if (!v) return -1;
        k->v = v; k->cap = cap;
    }
    k->v[k->n++] = p;
    return 0;
}

static void g_keep_free(g_kept *k) {
    for (int64_t i = 0; i < k->n; i++) free(k->v[i]);
    free(k->v);
    memset(k, 0, sizeof *k);
}

/* Grow *b (cap elements of `size` bytes, `used` of them in use) to hold `need`: realloc, or while
 * `shared` a copy whose old array is kept (readers without the lock may hold it); 0, or -1. */
static int g_grow_kept(void **b, int64_t *cap, int64_t used, int64_t need, size_t size, int shared, g_kept *k) {
    if (need <= *cap) return 0;
    int64_t c = *cap ? *cap : 64;
    while (c < need) c *= 2;
    if (!shared) {
        void *p = realloc(*b, (size_t)c * size);
        if (!p) return -1;
        *b = p; *cap = c;
        return 0;
    }
    void *p = malloc((size_t)c * size);
    if (!p) return -1;
    if (used) memcpy(p, *b, (size_t)used * size);
    if (*b && g_keep(k, *b) != 0) { free(p); return -1; }
    __atomic_store_n(b, p, __ATOMIC_RELEASE);
    *cap = c;
    return 0;
}

typedef struct {
    int64_t n, cap;          /* multisets */
    int64_t *off;            /* where multiset i starts in `pairs` (in int32 units) */
    int32_t *len;            /* its number of distinct colours */
    uint64_t *hash;
    int32_t *pairs; int64_t np, pcap;
    uint32_t *table;         /* id + 1 per slot, 0: empty; its mask stored before it (ms_slots) */
    int lock, shared;        /* (ND_THREADS) */
    g_kept kept;
} mstab;

/* Multiset `id`'s pairs and number of distinct colours (read without the table's lock). */
static inline const int32_t *ms_pairs(const mstab *t, int64_t id) {
    return __atomic_load_n(&t->pairs, __ATOMIC_ACQUIRE) + __atomic_load_n(&t->off, __ATOMIC_ACQUIRE)[id];
}

static inline int32_t ms_len(const mstab *t, int64_t id) { return __atomic_load_n(&t->len, __ATOMIC_ACQUIRE)[id]; }

static uint64_t ms_mix(uint64_t x) {
    x += 0x9E3779B97F4A7C15ULL;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    return x ^ (x >> 31);
}

static uint64_t ms_hash(const int32_t *pr, int32_t n) {
    uint64_t h = ms_mix((uint64_t)n);
    for (int32_t i = 0; i < n; i++)
        h += ms_mix(((uint64_t)(uint32_t)pr[2 * i] << 32) | (uint32_t)pr[2 * i + 1]);
    return h;
}

static int ms_same(const int32_t *a, const int32_t *b, int32_t n) {
    if (memcmp(a, b, 8 * (size_t)n) == 0) return 1;  /* the same pairs in the same order: the usual case */
    for (int32_t i = 0; i < n; i++) {
        int32_t c = a[2 * i], k = a[2 * i + 1], found = 0;
        for (int32_t j = 0; j < n; j++)
            if (b[2 * j] == c) { found = b[2 * j + 1] == k; break; }
        if (!found) return 0;
    }
    return 1;
}

/* A table of `size` empty slots (a power of two), its mask in the 8 bytes before it: a thread reading it
 * without the lock gets the slots and their mask with one load. */
static uint32_t *ms_slots(uint64_t size) {
    uint64_t *b = (uint64_t *)calloc((size_t)(size / 2 + 1), 8);
    if (!b) return NULL;
    b[0] = size - 1;
    return (uint32_t *)(b + 1);
}

static inline uint64_t ms_mask(const uint32_t *table) { return ((const uint64_t *)table)[-1]; }

static void *ms_slots_block(uint32_t *table) { return table ? (void *)((uint64_t *)table - 1) : NULL; }

static int ms_init(mstab *t) {
    memset(t, 0, sizeof *t);
    t->cap = 64; t->pcap = 256;
    t->off = (int64_t *)malloc(8 * (size_t)t->cap);
    t->len = (int32_t *)malloc(4 * (size_t)t->cap);
    t->hash = (uint64_t *)malloc(8 * (size_t)t->cap);
    t->pairs = (int32_t *)malloc(4 * (size_t)t->pcap);
    t->table = ms_slots(128);
    return (t->off && t->len && t->hash && t->pairs && t->table) ? 0 : -1;
}

static void ms_free(mstab *t) {
    free(t->off); free(t->len); free(t->hash); free(t->pairs); free(ms_slots_block(t->table));
    g_keep_free(&t->kept);
}

/* The id of the multiset of the n pairs `pr` (hash h), or -1 with the empty slot where it would go in
 * *slot. Safe without the table's lock: the slots, then each entry's arrays loaded after its slot, so
 * that they hold it (a multiset added meanwhile may be missed: the caller then looks under the lock). */
static int64_t ms_find(const mstab *t, const int32_t *pr, int32_t n, uint64_t h, uint64_t *slot) {
    const uint32_t *tab = __atomic_load_n(&t->table, __ATOMIC_ACQUIRE);
    uint64_t mask = ms_mask(tab);
    for (uint64_t i = h & mask;; i = (i + 1) & mask) {
        uint32_t e = __atomic_load_n(&tab[i], __ATOMIC_ACQUIRE);
        if (!e) { *slot = i; return -1; }
        int64_t id = (int64_t)e - 1;
        if (__atomic_load_n(&t->hash, __ATOMIC_ACQUIRE)[id] == h && ms_len(t, id) == n && ms_same(pr, ms_pairs(t, id), n))
            return id;
    }
}

/* The id of the multiset of the n pairs `pr` of hash h (a new id if it is new); -1 if memory runs out. */
static int64_t ms_intern_locked(mstab *t, const int32_t *pr, int32_t n, uint64_t h) {
    uint64_t mask = ms_mask(t->table), i;
    int64_t found = ms_find(t, pr, n, h, &i);
    if (found >= 0) return found;
    if (t->n == t->cap) {
        int64_t cap = t->cap;
        if (g_grow_kept((void **)&t->off, &cap, t->n, t->cap * 2, 8, t->shared, &t->kept) != 0) return -1;
        cap = t->cap;
        if (g_grow_kept((void **)&t->len, &cap, t->n, t->cap * 2, 4, t->shared, &t->kept) != 0) return -1;
        cap = t->cap;
        if (g_grow_kept((void **)&t->hash, &cap, t->n, t->cap * 2, 8, t->shared, &t->kept) != 0) return -1;
        t->cap = cap;
    }
    if (t->np + 2 * (int64_t)n > t->pcap
        && g_grow_kept((void **)&t->pairs, &t->pcap, t->np, t->np + 2 * (int64_t)n, 4, t->shared, &t->kept) != 0)
        return -1;
    if ((uint64_t)(t->n + 1) * 4 > (mask + 1) * 3) {
        uint64_t size = (mask + 1) * 2;
        uint32_t *tb = ms_slots(size);
        if (!tb) return -1;
        for (int64_t k = 0; k < t->n; k++) {
            uint64_t j = t->hash[k] & (size - 1);
            while (tb[j]) j = (j + 1) & (size - 1);
            tb[j] = (uint32_t)(k + 1);
        }
        void *old = ms_slots_block(t->table);
        if (!t->shared) free(old);
        else if (g_keep(&t->kept, old) != 0) { free(ms_slots_block(tb)); return -1; }  /* readers may hold it */
        __atomic_store_n(&t->table, tb, __ATOMIC_RELEASE);
        mask = size - 1;
        i = h & mask;
        while (t->table[i]) i = (i + 1) & mask;
    }
    int64_t id = t->n++;
    t->off[id] = t->np; t->len[id] = n; t->hash[id] = h;
    memcpy(t->pairs + t->np, pr, 8 * (size_t)n);
    t->np += 2 * (int64_t)n;
    __atomic_store_n(&t->table[i], (uint32_t)(id + 1), __ATOMIC_RELEASE);  /* published: its entry is written */
    return id;
}

/* As ms_intern_locked; while the tables are shared, a multiset already there is found without the lock. */
static int64_t ms_intern(mstab *t, const int32_t *pr, int32_t n) {
    uint64_t h = ms_hash(pr, n), slot;
    if (!t->shared) return ms_intern_locked(t, pr, n, h);
    int64_t found = ms_find(t, pr, n, h, &slot);
    if (found >= 0) return found;
    g_lock(&t->lock);
    int64_t id = ms_intern_locked(t, pr, n, h);
    g_unlock(&t->lock);
    return id;
}

/* The count of colour c in the n pairs pr. */
static int64_t ms_count(const int32_t *pr, int32_t n, int64_t c) {
    for (int32_t i = 0; i < n; i++) if (pr[2 * i] == c) return pr[2 * i + 1];
    return 0;
}

/* ---------------------------------------------------------------- the tables and a search's context */
typedef struct {
    int P, T;
    mstab *mk;               /* per place: its markings */
    mstab *dl;               /* per place: its deltas (consumed or produced tokens of a binding) */
    int32_t **be_of;         /* per transition: binding key -> binding element id (-1: none yet) */
    int64_t *be_size;        /* per transition: the number of binding keys */
    int32_t *be_t; int64_t *be_key; int64_t nbe, be_cap;
    int64_t *rcp;            /* per binding element: its recipe's offset in `pool` (-1: none yet) */
    int32_t *pool; int64_t npool, pool_cap;
    int be_lock, shared;     /* the binding elements and recipes (ND_THREADS) */
    g_kept kept;
    int contexts;            /* the contexts over these tables */
    uint8_t *be_open;        /* per transition: its binding keys are interned tuples (be_size grows) */
    /* interned values (colour sets without a finite layout, and the bindings of the transitions that
     * bind their values): per domain, a value's int64 leaves, leaf i as the pairs (2i, low 32 bits)
     * and (2i + 1, high 32 bits) of a multiset table, so that two values are one id iff their leaves
     * are equal, read and interned as markings are (without a lock where they are there already) */
    int ND; mstab *nd;
    /* timed places (the search of timed nets, one thread): per place, its timed colours (colour id,
     * timestamp), numbered in the order first met; a timed marking's pairs are (timed colour, count) */
    vmap *tc;                /* per place: (colour id, timestamp low, high) -> timed colour */
    int32_t **tc_col; int64_t **tc_ts; int64_t *ntc, *tc_cap;
} gtab;

typedef struct {
    gtab *tb;
    mstab *mk, *dl;          /* tb's */
    int32_t *buf; int64_t buf_cap;  /* scratch pairs */
    int64_t *bind; int64_t nb, bind_cap;  /* the bindings found, one after the other */
    int32_t *out; int64_t out_cap;  /* the entries of a result */
    int err;                 /* 1: an evaluation the Python engine must do (or report); 2: no memory */
    int depth;               /* calls of user functions in progress */
    int32_t **vw; int64_t *vw_cap;  /* per place: the untimed view of a timed marking (g_view) */
} gctx;

static int g_grow(void **b, int64_t *cap, int64_t need, size_t size) {
    if (need <= *cap) return 0;
    int64_t c = *cap ? *cap : 64;
    while (c < need) c *= 2;
    void *p = realloc(*b, (size_t)c * size);
    if (!p) return -1;
    *b = p; *cap = c;
    return 0;
}

static gctx *g_context(gtab *tb) {
    gctx *c = (gctx *)calloc(1, sizeof(gctx));
    if (!c) return NULL;
    c->tb = tb; c->mk = tb->mk; c->dl = tb->dl;
    c->vw = (int32_t **)calloc((size_t)tb->P + 1, sizeof(int32_t *));
    c->vw_cap = (int64_t *)calloc((size_t)tb->P + 1, sizeof(int64_t));
    if (!c->vw || !c->vw_cap) { free(c->vw); free(c->vw_cap); free(c); return NULL; }
    tb->contexts++;
    return c;
}

static void g_tab_free(gtab *tb) {
    for (int p = 0; p < tb->P; p++) { ms_free(&tb->mk[p]); ms_free(&tb->dl[p]); }
    for (int t = 0; t < tb->T; t++) free(tb->be_of[t]);
    for (int d = 0; d < tb->ND; d++) ms_free(&tb->nd[d]);
    free(tb->nd); free(tb->be_open);
    if (tb->tc) {
        for (int p = 0; p < tb->P; p++) { if (tb->tc[p].keys) vm_free(&tb->tc[p]); free(tb->tc_col[p]); free(tb->tc_ts[p]); }
        free(tb->tc); free(tb->tc_col); free(tb->tc_ts); free(tb->ntc); free(tb->tc_cap);
    }
    free(tb->mk); free(tb->dl); free(tb->be_of); free(tb->be_size); free(tb->be_t); free(tb->be_key);
    free(tb->rcp); free(tb->pool);
    g_keep_free(&tb->kept);
    free(tb);
}

static gctx *g_new(int P, int T, const int64_t *be_size) {
    gtab *tb = (gtab *)calloc(1, sizeof(gtab));
    if (!tb) return NULL;
    tb->P = P; tb->T = T;
    tb->mk = (mstab *)calloc((size_t)P + 1, sizeof(mstab));
    tb->dl = (mstab *)calloc((size_t)P + 1, sizeof(mstab));
    tb->be_of = (int32_t **)calloc((size_t)T + 1, sizeof(int32_t *));
    tb->be_size = (int64_t *)calloc((size_t)T + 1, sizeof(int64_t));
    if (!tb->mk || !tb->dl || !tb->be_of || !tb->be_size) { g_tab_free(tb); return NULL; }
    for (int p = 0; p < P; p++) if (ms_init(&tb->mk[p]) || ms_init(&tb->dl[p])) { g_tab_free(tb); return NULL; }
    for (int t = 0; t < T; t++) {  /* be_of[t]: allocated when first used */
        if (be_size[t] >= 0) { tb->be_size[t] = be_size[t]; continue; }
        if (!tb->be_open && !(tb->be_open = (uint8_t *)calloc((size_t)T + 1, 1))) { g_tab_free(tb); return NULL; }
        tb->be_open[t] = 1;  /* -1: keys interned, the table grows with them */
    }
    gctx *c = g_context(tb);
    if (!c) g_tab_free(tb);
    return c;
}

/* The n tables of interned values of c's tables (once, before any use): 0, or -1 without memory. */
static int g_nodes(gctx *c, int n) {
    gtab *tb = c->tb;
    tb->nd = (mstab *)calloc((size_t)n + 1, sizeof(mstab));
    if (!tb->nd) return -1;
    for (int d = 0; d < n; d++) {
        if (ms_init(&tb->nd[d])) return -1;
        tb->ND = d + 1;
    }
    return 0;
}

/* g_new with n tables of interned values. */
static gctx *g_new_interned(int P, int T, const int64_t *be_size, int n) {
    gctx *c = g_new(P, T, be_size);
    if (c && g_nodes(c, n)) { gen_free(c); return NULL; }
    return c;
}

/* The id of the value of `w` leaves x in domain d (a new id if it is new); -1 (c->err 2) without memory. */
static int64_t g_node(gctx *c, int d, const int64_t *x, int w) {
    int32_t pr[4 * w + 4];
    for (int i = 0; i < w; i++) {
        pr[4 * i] = 2 * i; pr[4 * i + 1] = (int32_t)(uint32_t)(uint64_t)x[i];
        pr[4 * i + 2] = 2 * i + 1; pr[4 * i + 3] = (int32_t)(uint32_t)((uint64_t)x[i] >> 32);
    }
    int64_t id = ms_intern(&c->tb->nd[d], pr, 2 * w);
    if (id < 0) c->err = 2;
    return id;
}

/* Leaf i of the value `id` of domain d, whose values have fewer than w leaves (a value the engine
 * interned that C cannot hold, an integer beyond 64 bits, has w: c->err, the engine evaluates it). */
static inline int64_t g_leaf(gctx *c, int d, int w, int64_t id, int i) {
    if (ms_len(&c->tb->nd[d], id) == 2 * w) { c->err = 1; return 0; }
    const int32_t *pr = ms_pairs(&c->tb->nd[d], id);
    return (int64_t)(((uint64_t)(uint32_t)pr[4 * i + 3] << 32) | (uint32_t)pr[4 * i + 1]);
}

/* Lists (ctables.ListDom): a list of domain d is the node [n, its n elements' leaves, ew each]; [-1, id]
 * is a list the engine made that C cannot hold (c->err: the engine evaluates what reads it). Every
 * function returns 0 at once after an error (its list argument may then be no id at all); one that finds
 * no value (hd of [], an index outside the list) sets c->err 1, so that the engine raises its exception. */
static inline int64_t g_lraw(gctx *c, int d, int64_t id, int64_t i) {
    const int32_t *pr = ms_pairs(&c->tb->nd[d], id);
    return (int64_t)(((uint64_t)(uint32_t)pr[4 * i + 3] << 32) | (uint32_t)pr[4 * i + 1]);
}

static inline int64_t g_llen(gctx *c, int d, int64_t id) {
    if (c->err) return 0;
    int64_t n = g_lraw(c, d, id, 0);
    if (n < 0) { c->err = 1; return 0; }
    return n;
}

static inline int64_t g_lelem(gctx *c, int d, int ew, int64_t id, int64_t i, int j) {
    int64_t n = g_llen(c, d, id);
    if (c->err) return 0;
    if (i < 0 || i >= n) { c->err = 1; return 0; }
    return g_lraw(c, d, id, 1 + i * ew + j);
}

/* The list whose node is b: b[0] its n elements, then their leaves (ew each); b is the caller's. */
static int64_t g_lnode(gctx *c, int d, int64_t *b, int64_t n, int ew) {
    int64_t w = 1 + n * ew;
    if (w > (1 << 14)) { c->err = 1; return 0; }  /* (g_node keeps 4 w + 4 ints on the stack) */
    b[0] = n;
    int64_t id = g_node(c, d, b, (int)w);
    return id < 0 ? 0 : id;
}

/* A node of n elements (ew leaves each) to fill from b[1] on, or NULL (c->err 2) without memory. */
static int64_t *g_lbuf(gctx *c, int64_t n, int ew) {
    int64_t *b = (int64_t *)malloc((size_t)(n * ew + 1) * sizeof(int64_t));
    if (!b) c->err = 2;
    return b;
}

/* Leaves [from, to) of list `id` into x (read from its pairs, as g_lraw does). */
static void g_lcopy(gctx *c, int d, int64_t id, int64_t from, int64_t to, int64_t *x) {
    const int32_t *pr = ms_pairs(&c->tb->nd[d], id);
    for (int64_t i = from; i < to; i++)
        *x++ = (int64_t)(((uint64_t)(uint32_t)pr[4 * i + 3] << 32) | (uint32_t)pr[4 * i + 1]);
}

/* The list of the n elements x (ew leaves each). */
static int64_t g_lmake(gctx *c, int d, int64_t n, int ew, const int64_t *x) {
    if (c->err) return 0;
    int64_t *b = g_lbuf(c, n, ew);
    if (!b) return 0;
    for (int64_t i = 0; i < n * ew; i++) b[1 + i] = x[i];
    int64_t id = g_lnode(c, d, b, n, ew);
    free(b);
    return id;
}

/* Elements [from, to) of list a, then elements [from2, to2) of list b (b < 0: none), in that order, or
 * the reverse of a's range (rev): the list they make. */
static int64_t g_lslice(gctx *c, int d, int ew, int64_t a, int64_t from, int64_t to, int64_t b, int64_t from2,
                        int64_t to2, int rev) {
    if (c->err) return 0;
    int64_t n = (to - from) + (b >= 0 ? to2 - from2 : 0);
    int64_t *x = g_lbuf(c, n, ew);
    if (!x) return 0;
    if (!rev) {
        g_lcopy(c, d, a, 1 + from * ew, 1 + to * ew, x + 1);
    } else {
        for (int64_t i = 0; i < to - from; i++)
            g_lcopy(c, d, a, 1 + (to - 1 - i) * ew, 1 + (to - i) * ew, x + 1 + i * ew);
    }
    if (b >= 0) g_lcopy(c, d, b, 1 + from2 * ew, 1 + to2 * ew, x + 1 + (to - from) * ew);
    int64_t id = g_lnode(c, d, x, n, ew);
    free(x);
    return id;
}

/* h :: a (h: the element's ew leaves). */
static int64_t g_lcons(gctx *c, int d, int ew, const int64_t *h, int64_t a) {
    int64_t n = g_llen(c, d, a);
    if (c->err) return 0;
    int64_t *x = g_lbuf(c, n + 1, ew);
    if (!x) return 0;
    for (int j = 0; j < ew; j++) x[1 + j] = h[j];
    g_lcopy(c, d, a, 1, 1 + n * ew, x + 1 + ew);
    int64_t id = g_lnode(c, d, x, n + 1, ew);
    free(x);
    return id;
}

/* a @ b */
static int64_t g_lapp(gctx *c, int d, int ew, int64_t a, int64_t b) {
    int64_t n = g_llen(c, d, a), m = g_llen(c, d, b);
    return c->err ? 0 : g_lslice(c, d, ew, a, 0, n, b, 0, m, 0);
}

/* tl a, rev a, List.take (a, k), List.drop (a, k) */
static int64_t g_ltl(gctx *c, int d, int ew, int64_t a) {
    int64_t n = g_llen(c, d, a);
    if (c->err) return 0;
    if (n == 0) { c->err = 1; return 0; }
    return g_lslice(c, d, ew, a, 1, n, -1, 0, 0, 0);
}

static int64_t g_lrev(gctx *c, int d, int ew, int64_t a) {
    int64_t n = g_llen(c, d, a);
    return c->err ? 0 : g_lslice(c, d, ew, a, 0, n, -1, 0, 0, 1);
}

static int64_t g_ltake(gctx *c, int d, int ew, int64_t a, int64_t k) {
    int64_t n = g_llen(c, d, a);
    if (c->err) return 0;
    if (k < 0 || k > n) { c->err = 1; return 0; }
    return g_lslice(c, d, ew, a, 0, k, -1, 0, 0, 0);
}

static int64_t g_ldrop(gctx *c, int d, int ew, int64_t a, int64_t k) {
    int64_t n = g_llen(c, d, a);
    if (c->err) return 0;
    if (k < 0 || k > n) { c->err = 1; return 0; }
    return g_lslice(c, d, ew, a, k, n, -1, 0, 0, 0);
}

/* mem a x (x: the element's ew leaves) */
static int64_t g_lmem(gctx *c, int d, int ew, int64_t a, const int64_t *x) {
    int64_t n = g_llen(c, d, a);
    if (c->err) return 0;
    for (int64_t i = 0; i < n; i++) {
        int j = 0;
        while (j < ew && g_lraw(c, d, a, 1 + i * ew + j) == x[j]) j++;
        if (j == ew) return 1;
    }
    return 0;
}

/* Free a context; the tables go with the last one. */
void gen_free(void *g) {
    gctx *c = (gctx *)g;
    if (!c) return;
    for (int p = 0; p < c->tb->P; p++) free(c->vw[p]);
    if (--c->tb->contexts == 0) g_tab_free(c->tb);
    free(c->vw); free(c->vw_cap);
    free(c->buf); free(c->bind); free(c->out); free(c);
}

#ifdef ND_THREADS
/* Another context over g's tables, for another thread: the tables are shared from now on (NULL without
 * memory). */
void *gen_clone(void *g) {
    gtab *tb = ((gctx *)g)->tb;
    tb->shared = 1;
    for (int p = 0; p < tb->P; p++) tb->mk[p].shared = tb->dl[p].shared = 1;
    for (int d = 0; d < tb->ND; d++) tb->nd[d].shared = 1;
    return g_context(tb);
}

/* The threads are done (their contexts freed): the tables are one thread's again, the arrays kept for
 * readers without a lock freed. */
void gen_unshare(void *g) {
    gtab *tb = ((gctx *)g)->tb;
    tb->shared = 0;
    g_keep_free(&tb->kept);
    for (int p = 0; p < tb->P; p++) {
        tb->mk[p].shared = tb->dl[p].shared = 0;
        g_keep_free(&tb->mk[p].kept);
        g_keep_free(&tb->dl[p].kept);
    }
    for (int d = 0; d < tb->ND; d++) {
        tb->nd[d].shared = 0;
        g_keep_free(&tb->nd[d].kept);
    }
}
#endif

/* The binding element of transition t with binding key `key` (a new one if it is new: *fresh = 1);
 * under the binding elements' lock while the tables are shared. */
static int64_t g_be(gctx *c, int t, int64_t key, int *fresh) {
    gtab *tb = c->tb;
    *fresh = 0;
    if (key < 0) { c->err = 1; return -1; }
    if (key >= tb->be_size[t]) {
        if (!tb->be_open || !tb->be_open[t]) { c->err = 1; return -1; }
        /* an interned key past the table: a larger copy, published before its size (g_recipe reads
         * the size first); the old one kept while readers without the lock may hold it */
        int64_t cap = tb->be_size[t] ? 2 * tb->be_size[t] : 64;
        while (cap <= key) cap *= 2;
        int32_t *of = (int32_t *)malloc(4 * (size_t)cap);
        if (!of) { c->err = 2; return -1; }
        memset(of, 0xFF, 4 * (size_t)cap);
        if (tb->be_size[t]) memcpy(of, tb->be_of[t], 4 * (size_t)tb->be_size[t]);
        if (tb->be_of[t]) {
            if (!tb->shared) free(tb->be_of[t]);
            else if (g_keep(&tb->kept, tb->be_of[t])) { free(of); c->err = 2; return -1; }
        }
        __atomic_store_n(&tb->be_of[t], of, __ATOMIC_RELEASE);
        __atomic_store_n(&tb->be_size[t], cap, __ATOMIC_RELEASE);
    }
    if (!tb->be_of[t]) {
        int32_t *of = (int32_t *)malloc(4 * (size_t)tb->be_size[t]);
        if (!of) { c->err = 2; return -1; }
        memset(of, 0xFF, 4 * (size_t)tb->be_size[t]);  /* -1: no binding element yet */
        __atomic_store_n(&tb->be_of[t], of, __ATOMIC_RELEASE);
    }
    int32_t be = tb->be_of[t][key];
    if (be >= 0) return be;
    if (tb->nbe == tb->be_cap) {
        int64_t cap = tb->be_cap, n = tb->nbe, need = cap ? 2 * cap : 256;
        if (g_grow_kept((void **)&tb->be_t, &cap, n, need, 4, tb->shared, &tb->kept)) { c->err = 2; return -1; }
        cap = tb->be_cap;
        if (g_grow_kept((void **)&tb->be_key, &cap, n, need, 8, tb->shared, &tb->kept)) { c->err = 2; return -1; }
        cap = tb->be_cap;
        if (g_grow_kept((void **)&tb->rcp, &cap, n, need, 8, tb->shared, &tb->kept)) { c->err = 2; return -1; }
        tb->be_cap = cap;
    }
    be = (int32_t)tb->nbe;
    tb->be_t[be] = t; tb->be_key[be] = key; tb->rcp[be] = -1;
    __atomic_store_n(&tb->nbe, tb->nbe + 1, __ATOMIC_RELEASE);
    __atomic_store_n(&tb->be_of[t][key], be, __ATOMIC_RELEASE);
    *fresh = 1;
    return be;
}

/* Room for `width` more int32 in the recipes' pool (under the binding elements' lock). */
static int g_pool(gctx *c, int64_t width) {
    gtab *tb = c->tb;
    return g_grow_kept((void **)&tb->pool, &tb->pool_cap, tb->npool, tb->npool + width, 4, tb->shared, &tb->kept);
}

/* Binding element `be`'s recipe is the `width` int32 written at the end of the pool: published. */
static void g_recipe_done(gctx *c, int64_t be, int64_t width) {
    gtab *tb = c->tb;
    int64_t at = tb->npool;
    tb->npool += width;
    __atomic_store_n(&tb->rcp[be], at, __ATOMIC_RELEASE);
}

typedef int (*g_rcp_fn)(gctx *c, const int64_t *v, int64_t be);

/* The recipe of transition t's binding with key `key` and variables' values v (`make` writes it if it
 * is not there yet), and its binding element in *be; NULL if c->err says why not. Without a lock when
 * both are there already. */
static const int32_t *g_recipe(gctx *c, int t, int64_t key, const int64_t *v, g_rcp_fn make, int64_t *be) {
    gtab *tb = c->tb;
    if (key < 0) { c->err = 1; return NULL; }
    /* (a key past the size: g_be, under the lock, says whether it is one) */
    const int64_t size = __atomic_load_n(&tb->be_size[t], __ATOMIC_ACQUIRE);
    const int32_t *of = __atomic_load_n(&tb->be_of[t], __ATOMIC_ACQUIRE);
    if (of && key < size) {
        int32_t b = __atomic_load_n(&of[key], __ATOMIC_ACQUIRE);
        if (b >= 0) {
            int64_t r = __atomic_load_n(&__atomic_load_n(&tb->rcp, __ATOMIC_ACQUIRE)[b], __ATOMIC_ACQUIRE);
            if (r >= 0) { *be = b; return __atomic_load_n(&tb->pool, __ATOMIC_ACQUIRE) + r; }
        }
    }
    int fresh;
    const int32_t *recipe = NULL;
    if (tb->shared) g_lock(&tb->be_lock);
    int64_t b = g_be(c, t, key, &fresh);
    if (!c->err && tb->rcp[b] < 0) make(c, v, b);
    if (!c->err) recipe = tb->pool + tb->rcp[b];  /* (the pool may grow once the lock is released) */
    if (tb->shared) g_unlock(&tb->be_lock);
    *be = b;
    return recipe;
}

/* The id of delta pairs pr (n of them) of place p; -1 for none (n == 0 and not `keep_empty`). */
static int64_t g_delta(gctx *c, int p, const int32_t *pr, int32_t n) {
    int64_t id = ms_intern(&c->dl[p], pr, n);
    if (id < 0) c->err = 2;
    return id;
}

/* Marking `cur` of place p minus (sign < 0) or plus (sign > 0) delta `did`, interned. */
static int64_t g_apply(gctx *c, int p, int64_t cur, int64_t did, int sign) {
    mstab *m = &c->mk[p], *d = &c->dl[p];
    int32_t n = ms_len(m, cur), dn = ms_len(d, did);
    if (g_grow((void **)&c->buf, &c->buf_cap, 2 * ((int64_t)n + dn) + 2, 4)) { c->err = 2; return -1; }
    int32_t *b = c->buf;
    memcpy(b, ms_pairs(m, cur), 8 * (size_t)n);
    const int32_t *dp = ms_pairs(d, did);
    for (int32_t i = 0; i < dn; i++) {
        int32_t col = dp[2 * i], k = dp[2 * i + 1], j = 0;
        while (j < n && b[2 * j] != col) j++;
        if (sign > 0) {
            if (j < n) b[2 * j + 1] += k;
            else { b[2 * n] = col; b[2 * n + 1] = k; n++; }
        } else {
            if (j == n || b[2 * j + 1] < k) { c->err = 1; return -1; }
            if (b[2 * j + 1] > k) b[2 * j + 1] -= k;
            else { memmove(b + 2 * j, b + 2 * j + 2, 8 * (size_t)(n - j - 1)); n--; }
        }
    }
    int64_t id = ms_intern(m, b, n);
    if (id < 0) c->err = 2;
    return id;
}

/* Accumulate count k of colour col into the n pairs of b (a dict's `d[v] = d.get(v, 0) + k`). */
static int32_t g_acc(int32_t *b, int32_t n, int64_t col, int64_t k) {
    for (int32_t j = 0; j < n; j++) if (b[2 * j] == col) { b[2 * j + 1] += (int32_t)k; return n; }
    b[2 * n] = (int32_t)col; b[2 * n + 1] = (int32_t)k;
    return n + 1;
}

/* Whether the n pairs `need` are all in the marking pr/np (ENOUGH). */
static int g_enough(const int32_t *pr, int32_t np, const int32_t *need, int32_t n) {
    for (int32_t j = 0; j < n; j++)
        if (need[2 * j + 1] && ms_count(pr, np, need[2 * j]) < need[2 * j + 1]) return 0;
    return 1;
}

/* Integer arithmetic: the Python engine's integers are unbounded, so a result that does not fit 64 bits
   is handed back to Python (c->err) instead of wrapping around. */
static int64_t g_add(gctx *c, int64_t a, int64_t b) {
    int64_t r;
    if (__builtin_add_overflow(a, b, &r)) { c->err = 1; return 0; }
    return r;
}

static int64_t g_sub(gctx *c, int64_t a, int64_t b) {
    int64_t r;
    if (__builtin_sub_overflow(a, b, &r)) { c->err = 1; return 0; }
    return r;
}

static int64_t g_mul(gctx *c, int64_t a, int64_t b) {
    int64_t r;
    if (__builtin_mul_overflow(a, b, &r)) { c->err = 1; return 0; }
    return r;
}

static int64_t g_neg(gctx *c, int64_t a) {
    if (a == INT64_MIN) { c->err = 1; return 0; }
    return -a;
}

static int64_t g_div(gctx *c, int64_t a, int64_t b) {
    if (b == 0 || (a == INT64_MIN && b == -1)) { c->err = 1; return 0; }
    int64_t q = a / b;
    if ((a % b != 0) && ((a < 0) != (b < 0))) q--;
    return q;
}

static int64_t g_mod(gctx *c, int64_t a, int64_t b) {
    if (b == 0) { c->err = 1; return 0; }
    if (b == -1) return 0;
    int64_t r = a % b;
    if (r != 0 && ((r < 0) != (b < 0))) r += b;
    return r;
}

static int64_t g_fail(gctx *c) { c->err = 1; return 0; }


/* ---------------------------------------------------------------- timed places (the search of timed nets) */
/* Set up the timed colours' tables (once): 0, or -1 without memory. */
static int g_timed_init(gtab *tb) {
    if (tb->tc) return 0;
    int P = tb->P;
    tb->tc = (vmap *)calloc((size_t)P + 1, sizeof(vmap));
    tb->tc_col = (int32_t **)calloc((size_t)P + 1, sizeof(int32_t *));
    tb->tc_ts = (int64_t **)calloc((size_t)P + 1, sizeof(int64_t *));
    tb->ntc = (int64_t *)calloc((size_t)P + 1, sizeof(int64_t));
    tb->tc_cap = (int64_t *)calloc((size_t)P + 1, sizeof(int64_t));
    if (!tb->tc || !tb->tc_col || !tb->tc_ts || !tb->ntc || !tb->tc_cap) return -1;
    for (int p = 0; p < P; p++) if (vm_init(&tb->tc[p], 3) != 0) return -1;
    return 0;
}

/* The timed colour (colour id `col`, timestamp ts) of place p (a new one if it is new); -1 if memory runs out. */
static int64_t g_tid(gctx *c, int p, int64_t col, int64_t ts) {
    gtab *tb = c->tb;
    if (!tb->tc && g_timed_init(tb) != 0) { c->err = 2; return -1; }
    uint32_t k[3] = {(uint32_t)col, (uint32_t)(uint64_t)ts, (uint32_t)((uint64_t)ts >> 32)};
    int64_t id = vm_get(&tb->tc[p], k);
    if (id >= 0) return id;
    id = tb->ntc[p];
    if (id >= tb->tc_cap[p]) {  /* both arrays grow to the same capacity */
        int64_t cap = tb->tc_cap[p] ? 2 * tb->tc_cap[p] : 64;
        int32_t *ca = (int32_t *)realloc(tb->tc_col[p], (size_t)cap * 4);
        if (!ca) { c->err = 2; return -1; }
        tb->tc_col[p] = ca;
        int64_t *ta = (int64_t *)realloc(tb->tc_ts[p], (size_t)cap * 8);
        if (!ta) { c->err = 2; return -1; }
        tb->tc_ts[p] = ta;
        tb->tc_cap[p] = cap;
    }
    tb->tc_col[p][id] = (int32_t)col; tb->tc_ts[p][id] = ts;
    tb->ntc[p] = id + 1;
    if (vm_put(&tb->tc[p], k, id) != 0) { c->err = 2; return -1; }
    return id;
}

static inline int32_t g_tcol(const gctx *c, int p, int64_t tid) { return c->tb->tc_col[p][tid]; }
static inline int64_t g_tts(const gctx *c, int p, int64_t tid) { return c->tb->tc_ts[p][tid]; }

/* The untimed view of timed marking `id` of place p: its (colour id, count) pairs in the order the colours
 * first occur (the engine's `_untimed`), in a buffer of the context's own for p; *n their number. */
static const int32_t *g_view(gctx *c, int p, int64_t id, int32_t *n) {
    int32_t m = ms_len(&c->mk[p], id);
    const int32_t *pr = ms_pairs(&c->mk[p], id);
    *n = 0;
    if (g_grow((void **)&c->vw[p], &c->vw_cap[p], 2 * (int64_t)m + 2, 4) != 0) { c->err = 2; return c->vw[p]; }
    int32_t *b = c->vw[p], k = 0;
    for (int32_t i = 0; i < m; i++) k = g_acc(b, k, g_tcol(c, p, pr[2 * i]), pr[2 * i + 1]);
    *n = k;
    return b;
}

/* The earliest time the tokens `need` ((colour id, count) pairs) are all ready in timed marking `id` of
 * place p (the engine's `ready_time`): for each colour, the timestamp of its need-th earliest token. */
static int64_t g_ready(gctx *c, int p, int64_t id, const int32_t *need, int32_t nn) {
    int32_t m = ms_len(&c->mk[p], id);
    const int32_t *pr = ms_pairs(&c->mk[p], id);
    int64_t ready = INT64_MIN;
    for (int32_t j = 0; j < nn; j++) {
        int32_t col = need[2 * j];
        int64_t want = need[2 * j + 1], prev = INT64_MIN;
        if (want <= 0) continue;
        for (;;) {  /* the timestamps of the colour in increasing order, with their counts */
            int64_t best = INT64_MAX, cnt = 0;
            for (int32_t i = 0; i < m; i++) {
                if (g_tcol(c, p, pr[2 * i]) != col) continue;
                int64_t ts = g_tts(c, p, pr[2 * i]);
                if (ts > prev && ts < best) { best = ts; cnt = pr[2 * i + 1]; }
            }
            if (best == INT64_MAX && cnt == 0) { c->err = 1; return 0; }
            want -= cnt;
            prev = best;
            if (want <= 0) break;
        }
        if (prev > ready) ready = prev;
    }
    return ready;
}

/* The marking of place p after a binding occurring at time f (the engine's `_writes` for a timed place or
 * a place a reset arc empties): marking `cur` less the tokens `cons` ((colour id, count) pairs; from a
 * timed place, for each colour the tokens with the largest timestamps not after f), emptied if `reset`,
 * plus the tokens `prod` ((colour id, count, timestamp) triples; a timestamp only on a timed place),
 * interned. */
static int64_t g_rewrite(gctx *c, int p, int timed, int64_t cur, const int32_t *cons, int32_t nc, int reset,
                         const int64_t *prod, int32_t np, int64_t f) {
    mstab *mk = &c->mk[p];
    int32_t n = ms_len(mk, cur);
    if (g_grow((void **)&c->buf, &c->buf_cap, 2 * ((int64_t)n + np) + 2, 4)) { c->err = 2; return -1; }
    int32_t *b = c->buf;
    memcpy(b, ms_pairs(mk, cur), 8 * (size_t)n);
    for (int32_t j = 0; j < nc; j++) {
        int32_t col = cons[2 * j];
        int64_t want = cons[2 * j + 1];
        while (want > 0) {
            int32_t at = -1;
            if (timed) {
                int64_t best = INT64_MIN;
                for (int32_t i = 0; i < n; i++) {
                    if (g_tcol(c, p, b[2 * i]) != col) continue;
                    int64_t ts = g_tts(c, p, b[2 * i]);
                    if (ts <= f && (at < 0 || ts > best)) { best = ts; at = i; }
                }
            } else {
                for (int32_t i = 0; i < n; i++) if (b[2 * i] == col) { at = i; break; }
            }
            if (at < 0) { c->err = 1; return -1; }
            int64_t k = b[2 * at + 1], take = k < want ? k : want;
            want -= take;
            if (k == take) { memmove(b + 2 * at, b + 2 * at + 2, 8 * (size_t)(n - at - 1)); n--; }
            else b[2 * at + 1] = (int32_t)(k - take);
        }
    }
    if (reset) n = 0;
    for (int32_t j = 0; j < np; j++) {
        int64_t k = prod[3 * j + 1];
        if (!k) continue;
        int64_t col = timed ? g_tid(c, p, prod[3 * j], prod[3 * j + 2]) : prod[3 * j];
        if (col < 0) return -1;
        b = c->buf;
        n = g_acc(b, n, col, k);
    }
    int64_t id = ms_intern(mk, c->buf, n);
    if (id < 0) c->err = 2;
    return id;
}

/* Timed marking `id` of place p with every timestamp moved back by f (none below 0), interned (the
 * engine's `_shift`). */
static int64_t g_shift(gctx *c, int p, int64_t id, int64_t f) {
    mstab *mk = &c->mk[p];
    int32_t n = ms_len(mk, id);
    if (g_grow((void **)&c->buf, &c->buf_cap, 2 * (int64_t)n + 2, 4)) { c->err = 2; return -1; }
    int32_t k = 0;
    for (int32_t i = 0; i < n; i++) {
        const int32_t *pr = ms_pairs(mk, id);
        int64_t ts = g_tts(c, p, pr[2 * i]) - f;
        int64_t t2 = g_tid(c, p, g_tcol(c, p, pr[2 * i]), ts > 0 ? ts : 0);
        if (t2 < 0) return -1;
        k = g_acc(c->buf, k, t2, pr[2 * i + 1]);
    }
    int64_t r = ms_intern(mk, c->buf, k);
    if (r < 0) c->err = 2;
    return r;
}

/* ---------------------------------------------------------------- exchange with the Python engine */
int64_t gen_count(void *g, int what, int p) {
    gctx *c = (gctx *)g;
    if (what == 2) return c->tb->nbe;
    return (what ? c->dl : c->mk)[p].n;
}

int32_t gen_ms_len(void *g, int what, int p, int64_t id) { gctx *c = (gctx *)g; return (what ? c->dl : c->mk)[p].len[id]; }

int32_t *gen_ms_pairs(void *g, int what, int p, int64_t id) {
    gctx *c = (gctx *)g;
    mstab *t = &(what ? c->dl : c->mk)[p];
    return t->pairs + t->off[id];
}

/* The table's arrays: where each multiset starts in `pairs`, its length, and the pairs themselves. */
int64_t gen_ms_table(void *g, int what, int p, int64_t **off, int32_t **len, int32_t **pairs) {
    gctx *c = (gctx *)g;
    mstab *t = &(what ? c->dl : c->mk)[p];
    *off = t->off; *len = t->len; *pairs = t->pairs;
    return t->n;
}

int64_t gen_ms_put(void *g, int what, int p, const int32_t *pr, int32_t n) {
    gctx *c = (gctx *)g;
    return ms_intern(&(what ? c->dl : c->mk)[p], pr, n);
}

int64_t gen_be_key(void *g, int64_t be, int32_t *t) {
    gctx *c = (gctx *)g;
    *t = c->tb->be_t[be];
    return c->tb->be_key[be];
}

int64_t gen_be_put(void *g, int t, int64_t key) {
    gctx *c = (gctx *)g;
    gtab *tb = c->tb;
    int fresh;
    c->err = 0;
    if (key < 0) {  /* a binding the C code does not number: kept for its id only */
        int64_t saved = tb->be_size[t];
        tb->be_size[t] = 1;
        int32_t *saved_of = tb->be_of[t], slot = -1;
        tb->be_of[t] = &slot;
        int64_t be = g_be(c, t, 0, &fresh);
        tb->be_of[t] = saved_of; tb->be_size[t] = saved;
        if (be >= 0) tb->be_key[be] = -1;
        return c->err ? -1 : be;
    }
    int64_t be = g_be(c, t, key, &fresh);
    return c->err ? -1 : be;
}

/* Domain d's interned values: their number; the id of the value of w leaves x (-1 without memory); the
 * leaves of value `id` into x (at most cap of them), and their number. */
int64_t gen_node_count(void *g, int d) { return ((gctx *)g)->tb->nd[d].n; }

int64_t gen_node_put(void *g, int d, const int64_t *x, int w) {
    gctx *c = (gctx *)g;
    c->err = 0;
    int64_t id = g_node(c, d, x, w);
    return c->err ? -1 : id;
}

int gen_node_len(void *g, int d, int64_t id) { return ms_len(&((gctx *)g)->tb->nd[d], id) / 2; }

int gen_node_get(void *g, int d, int64_t id, int64_t *x, int cap) {
    gctx *c = (gctx *)g;
    const int32_t *pr = ms_pairs(&c->tb->nd[d], id);
    int w = ms_len(&c->tb->nd[d], id) / 2;
    if (w > cap) w = cap;
    for (int i = 0; i < w; i++) x[i] = (int64_t)(((uint64_t)(uint32_t)pr[4 * i + 3] << 32) | (uint32_t)pr[4 * i + 1]);
    return w;
}

/* Place p's timed colour (colour id, timestamp), interned; -1 without memory. */
int64_t gen_tid_put(void *g, int p, int64_t col, int64_t ts) {
    gctx *c = (gctx *)g;
    c->err = 0;
    int64_t id = g_tid(c, p, col, ts);
    return c->err ? -1 : id;
}

/* Place p's timed colours: their number, and their colour ids and timestamps in *col and *ts. */
int64_t gen_tid_table(void *g, int p, int32_t **col, int64_t **ts) {
    gctx *c = (gctx *)g;
    gtab *tb = c->tb;
    if (!tb->tc) { *col = NULL; *ts = NULL; return 0; }
    *col = tb->tc_col[p]; *ts = tb->tc_ts[p];
    return tb->ntc[p];
}
