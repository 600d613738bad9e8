/* The run-time of the C generated from a net's inscriptions (cpn/engine/ccodegen.py): interned place
 * markings, deltas and binding elements in native memory, numbered exactly as the compiled Python engine
 * numbers them (cpn/engine/compiled.py), so that both give the same states and binding elements.
 *
 * A multiset is a list of (colour id, count) pairs in the order its colours were first added: the order of
 * the Python dict the engine builds, which is the order its tokens (and so the bindings found in it) are
 * enumerated in. Two lists with the same pairs in any order are the same multiset: the table finds it by
 * an order-independent hash and keeps the order of the first list it was given.
 */

typedef struct {
    int64_t n, cap;          /* multisets */
    int64_t *off;            /* where multiset i starts in `pairs` (in int32 units) */
    int32_t *len;            /* its number of distinct colours */
    uint64_t *hash;
    int32_t *pairs; int64_t np, pcap;
    uint32_t *table; uint64_t mask;   /* id + 1 per slot, 0: empty */
} mstab;

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

static int ms_init(mstab *t) {
    memset(t, 0, sizeof *t);
    t->cap = 64; t->pcap = 256;
    t->off = (int64_t *)malloc(8 * (size_t)t->cap);
    t->len = (int32_t *)malloc(4 * (size_t)t->cap);
    t->hash = (uint64_t *)malloc(8 * (size_t)t->cap);
    t->pairs = (int32_t *)malloc(4 * (size_t)t->pcap);
    t->table = (uint32_t *)calloc(128, 4);
    t->mask = 127;
    return (t->off && t->len && t->hash && t->pairs && t->table) ? 0 : -1;
}

static void ms_free(mstab *t) { free(t->off); free(t->len); free(t->hash); free(t->pairs); free(t->table); }

/* The id of the multiset of the n pairs `pr` (a new id if it is new); -1 if memory runs out. */
static int64_t ms_intern(mstab *t, const int32_t *pr, int32_t n) {
    uint64_t h = ms_hash(pr, n);
    uint64_t i = h & t->mask;
    for (;;) {
        uint32_t e = t->table[i];
        if (!e) break;
        int64_t id = (int64_t)e - 1;
        if (t->hash[id] == h && t->len[id] == n && ms_same(pr, t->pairs + t->off[id], n)) return id;
        i = (i + 1) & t->mask;
    }
    if (t->n == t->cap) {
        int64_t cap = t->cap * 2;
        int64_t *off = (int64_t *)realloc(t->off, 8 * (size_t)cap);
        if (!off) return -1;
        t->off = off;
        int32_t *len = (int32_t *)realloc(t->len, 4 * (size_t)cap);
        if (!len) return -1;
        t->len = len;
        uint64_t *hs = (uint64_t *)realloc(t->hash, 8 * (size_t)cap);
        if (!hs) return -1;
        t->hash = hs; t->cap = cap;
    }
    if (t->np + 2 * (int64_t)n > t->pcap) {
        int64_t cap = t->pcap;
        while (cap < t->np + 2 * (int64_t)n) cap *= 2;
        int32_t *p = (int32_t *)realloc(t->pairs, 4 * (size_t)cap);
        if (!p) return -1;
        t->pairs = p; t->pcap = cap;
    }
    if ((uint64_t)(t->n + 1) * 4 > (t->mask + 1) * 3) {
        uint64_t size = (t->mask + 1) * 2;
        uint32_t *tb = (uint32_t *)calloc(size, 4);
        if (!tb) return -1;
        for (int64_t k = 0; k < t->n; k++) {
            uint64_t j = t->hash[k] & (size - 1);
            while (tb[j]) j = (j + 1) & (size - 1);
            tb[j] = (uint32_t)(k + 1);
        }
        free(t->table); t->table = tb; t->mask = size - 1;
        i = h & t->mask;
        while (t->table[i]) i = (i + 1) & t->mask;
    }
    int64_t id = t->n++;
    t->off[id] = t->np; t->len[id] = n; t->hash[id] = h;
    memcpy(t->pairs + t->np, pr, 8 * (size_t)n);
    t->np += 2 * (int64_t)n;
    t->table[i] = (uint32_t)(id + 1);
    return id;
}

/* The count of colour c in the n pairs pr. */
static int64_t ms_count(const int32_t *pr, int32_t n, int64_t c) {
    for (int32_t i = 0; i < n; i++) if (pr[2 * i] == c) return pr[2 * i + 1];
    return 0;
}

/* ---------------------------------------------------------------- the context of one search */
typedef struct {
    int P, T;
    mstab *mk;               /* per place: its markings */
    mstab *dl;               /* per place: its deltas (consumed or produced tokens of a binding) */
    int32_t **be_of;         /* per transition: binding key -> binding element id (-1: none yet) */
    int64_t *be_size;        /* per transition: the number of binding keys */
    int32_t *be_t; int64_t *be_key; int64_t nbe, be_cap;
    int64_t *rcp; int64_t rcp_cap;  /* per binding element: its recipe's offset in `pool` (-1: none yet) */
    int32_t *pool; int64_t npool, pool_cap;
    int32_t *buf; int64_t buf_cap;  /* scratch pairs */
    int64_t *bind; int64_t nb, bind_cap;  /* the bindings found, one after the other */
    int32_t *out; int64_t out_cap;  /* the entries of a result */
    int err;                 /* 1: an evaluation the Python engine must do (or report); 2: no memory */
    int depth;               /* calls of user functions in progress */
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

static gctx *g_new(int P, int T, const int64_t *be_size) {
    gctx *c = (gctx *)calloc(1, sizeof(gctx));
    if (!c) return NULL;
    c->P = P; c->T = T;
    c->mk = (mstab *)calloc((size_t)P + 1, sizeof(mstab));
    c->dl = (mstab *)calloc((size_t)P + 1, sizeof(mstab));
    c->be_of = (int32_t **)calloc((size_t)T + 1, sizeof(int32_t *));
    c->be_size = (int64_t *)calloc((size_t)T + 1, sizeof(int64_t));
    if (!c->mk || !c->dl || !c->be_of || !c->be_size) return NULL;
    for (int p = 0; p < P; p++) if (ms_init(&c->mk[p]) || ms_init(&c->dl[p])) return NULL;
    for (int t = 0; t < T; t++) c->be_size[t] = be_size[t];  /* be_of[t]: allocated when first used */
    return c;
}

void gen_free(void *g) {
    gctx *c = (gctx *)g;
    if (!c) return;
    for (int p = 0; p < c->P; p++) { ms_free(&c->mk[p]); ms_free(&c->dl[p]); }
    for (int t = 0; t < c->T; t++) free(c->be_of[t]);
    free(c->mk); free(c->dl); free(c->be_of); free(c->be_size); free(c->be_t); free(c->be_key);
    free(c->rcp); free(c->pool); free(c->buf); free(c->bind); free(c->out); free(c);
}

/* The binding element of transition t with binding key `key` (a new one if it is new: *fresh = 1). */
static int64_t g_be(gctx *c, int t, int64_t key, int *fresh) {
    *fresh = 0;
    if (key < 0 || key >= c->be_size[t]) { c->err = 1; return -1; }
    if (!c->be_of[t]) {
        c->be_of[t] = (int32_t *)malloc(4 * (size_t)c->be_size[t]);
        if (!c->be_of[t]) { c->err = 2; return -1; }
        memset(c->be_of[t], 0xFF, 4 * (size_t)c->be_size[t]);  /* -1: no binding element yet */
    }
    int32_t be = c->be_of[t][key];
    if (be >= 0) return be;
    if (c->nbe == c->be_cap) {
        int64_t cap = c->be_cap ? 2 * c->be_cap : 256;
        int32_t *bt = (int32_t *)realloc(c->be_t, 4 * (size_t)cap);
        if (!bt) { c->err = 2; return -1; }
        c->be_t = bt;
        int64_t *bk = (int64_t *)realloc(c->be_key, 8 * (size_t)cap);
        if (!bk) { c->err = 2; return -1; }
        c->be_key = bk;
        int64_t *r = (int64_t *)realloc(c->rcp, 8 * (size_t)cap);
        if (!r) { c->err = 2; return -1; }
        c->rcp = r; c->be_cap = c->rcp_cap = cap;
    }
    be = (int32_t)c->nbe++;
    c->be_t[be] = t; c->be_key[be] = key; c->rcp[be] = -1;
    c->be_of[t][key] = be;
    *fresh = 1;
    return be;
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
    int32_t n = m->len[cur], dn = d->len[did];
    if (g_grow((void **)&c->buf, &c->buf_cap, 2 * ((int64_t)n + dn) + 2, 4)) { c->err = 2; return -1; }
    int32_t *b = c->buf;
    memcpy(b, m->pairs + m->off[cur], 8 * (size_t)n);
    const int32_t *dp = d->pairs + d->off[did];
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

/* ---------------------------------------------------------------- exchange with the Python engine */
int64_t gen_count(void *g, int what, int p) {
    gctx *c = (gctx *)g;
    if (what == 2) return c->nbe;
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
    *t = c->be_t[be];
    return c->be_key[be];
}

int64_t gen_be_put(void *g, int t, int64_t key) {
    gctx *c = (gctx *)g;
    int fresh;
    c->err = 0;
    if (key < 0) {  /* a binding the C code does not number: kept for its id only */
        int64_t saved = c->be_size[t];
        c->be_size[t] = 1;
        int32_t *saved_of = c->be_of[t], slot = -1;
        c->be_of[t] = &slot;
        int64_t be = g_be(c, t, 0, &fresh);
        c->be_of[t] = saved_of; c->be_size[t] = saved;
        if (be >= 0) c->be_key[be] = -1;
        return c->err ? -1 : be;
    }
    int64_t be = g_be(c, t, key, &fresh);
    return c->err ? -1 : be;
}
