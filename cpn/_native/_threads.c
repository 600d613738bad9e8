/* The multi-threaded native search (`--workers N` on a net whose transitions are all in generated C).
 *
 * Compiled after _packed.c and _search.c (whose store, caches and nd_search it uses) and before the net's
 * C (ND_GENERATED): gen_group and gen_add compute what a cache misses.
 *
 * N threads, each owning the part of the states whose hash (th_owner, independent of the store's own
 * hash) falls to it: a part is a store (_packed.c) of its own, touched by its owner only, so the stores
 * need no lock. The search is level-synchronous:
 *   phase A: every thread expands the states of the current level it owns; a successor it owns is stored
 *            at once, one another thread owns goes to that thread's inbox (the record, the source, the
 *            binding element and the arc's position), its arc left open;
 *   barrier; phase B: every thread stores the successors sent to it and closes the arcs that found them
 *            (it writes the destination into the sender's arc: each position is written by one thread);
 *   barrier: the next level is the states stored during this one; the search ends when no thread
 *            stored a state (or a stop was asked for or met: every thread sees the same decision).
 * So each state is stored first at its BFS depth, by an arc from the level above: its parent pointer
 * gives a shortest path, as in the one-process search.
 *
 * Caches: every thread has its own (an nd_search: group results per key of read values, written places'
 * new ids per (place, delta, old id)), read and filled without a lock; a cache whose results rarely recur
 * computes them anew (uncache_after, as in the one-process search). On a miss the thread runs the net's C
 * itself, in a context of its own (gen_clone) over the one set of tables of markings, deltas and binding
 * elements (one numbering for all threads), which _cnet.c changes under a lock per table. A key the C
 * cannot evaluate (gen_group or gen_add return -1: a division by zero, a value outside its colour set,
 * deep recursion) stops the search (TH_FALLBACK): the caller repeats it another way.
 *
 * A state is referred to as local id * N + part while the search runs; th_assemble numbers them
 * globally afterwards (expanded states first, by level, part and local id; then the unexpanded ones the
 * same way) and writes the one store, the arcs grouped by source, the offsets and the BFS parents.
 */

#include <pthread.h>
#include <time.h>

#include "_cnet.h"
#include "_threads.h"

enum { TH_RUNNING = -9, TH_STOPPED = 8, TH_FALLBACK = 7, TH_NO_MEMORY = 5, TH_COMPLETE = 9 };
#define TH_OPEN 0xFFFFFFFFu       /* an arc whose destination another thread stores */
#define TH_CHECK_EVERY 64         /* states expanded between looks at the limits and at a stop */

typedef struct {
    uint32_t *v; int64_t n, cap;
} th_buf;

static int th_push(th_buf *b, int64_t more) {
    if (!b->v) {
        b->cap = 256;
        if (!(b->v = (uint32_t *)malloc(4 * (size_t)b->cap))) return -1;
    }
    return grow((void **)&b->v, &b->cap, b->n + more, 4);
}

typedef struct {
    th_search *h;
    int me;
    cs_store *st;            /* the states this thread owns: local id -> record (K uint32 fields) */
    nd_search *d;            /* its caches and scratch buffers */
    void *gen;               /* its context of the net's C */
    th_buf parent;           /* per local state: its parent's reference (TH_OPEN: none) and binding element */
    th_buf parent_be;
    int64_t *lv; int64_t nlv, lv_cap;  /* lv[l]: the first local id of level l */
    int64_t head, end;       /* local ids below head are expanded; the current level ends at end */
    th_buf aend;             /* per expanded state: where its arcs end (two uint32: int64) */
    th_buf dst, bes;         /* per arc: the destination's reference, the binding element */
    th_buf *out;             /* per thread: the successors sent to it (K + 4 uint32 each) */
    th_buf own;              /* the owners of the successors of the state being expanded */
    int64_t nnew, stored;    /* states stored during this level and in all, as phase B left them */
    int saw_stop, level_done;
    int64_t computed;        /* results computed by the net's C (cache misses and uncached results) */
    uint32_t be_max;         /* the largest binding element of its arcs */
    double wait;             /* seconds spent at the barriers */
    double cpu_a, cpu_b;     /* the thread's CPU seconds expanding (phase A) and storing what it was sent (B) */
    /* published for the limits and the progress of the others (written by this thread only) */
    int64_t pub_states, pub_arcs, pub_pending;
    pthread_t tid;
    char pad[64];
} th_part;

struct th_search {
    int N, K;
    th_part *parts;
    uint64_t *mul;           /* per field: the odd constant of the owner's hash */
    void *gen;               /* the caller's context of the net's C (its tables are shared while the threads run) */
    pthread_barrier_t bar;
    int stop;                /* 0, or why the search stops (the first reason set wins) */
    int64_t max_states, max_arcs, levels;
    pthread_mutex_t done_lock;
    pthread_cond_t done_cond;
    int running, started, joined;
};

static void th_set_stop(th_search *h, int why) { __sync_bool_compare_and_swap(&h->stop, 0, why); }

/* Which thread owns a state: a mix of the sum of its place ids each times its own odd constant (mul; a
 * successor's sum is its state's plus the changes); independent of the store's own hash, so that a
 * part's table uses all of its slots. */
static inline int th_mix_owner(uint64_t x, int N) {
    if (N == 1) return 0;
    x ^= x >> 31; x *= 0x94D049BB133111EBULL; x ^= x >> 29; x *= 0xBF58476D1CE4E5B9ULL; x ^= x >> 32;
    return (int)(((x & 0xFFFFFFFFu) * (uint64_t)N) >> 32);
}

static int th_owner(const th_search *h, const uint32_t *t) {
    uint64_t x = 0;
    for (int f = 0; f < h->K; f++) x += t[f] * h->mul[f];
    return th_mix_owner(x, h->N);
}

/* Group g's result for `key` (the read values of the state being expanded): computed by the net's C
 * into the thread's cache, or into its scratch for a group whose results are not cached; 0 with its
 * offset in *o (in d->tmp if d->in_tmp[g], else in d->res), or why the search must stop. */
static int th_group(th_part *p, int g, const uint32_t *key, int64_t *o) {
    nd_search *d = p->d;
    d->in_tmp[g] = d->uncached[g];
    if (!d->uncached[g]) {
        *o = vm_get(&d->groups[g], key);
        nd_judge(&d->looks[g], &d->misses[g], &d->uncached[g], d->uncache_after, *o < 0);
        if (*o >= 0) return 0;
    }
    p->computed++;
    d->scratch = d->in_tmp[g];
    int rc = gen_group(p->gen, d, g, key);
    d->scratch = 0;
    if (rc != 0) return rc == -2 ? TH_NO_MEMORY : TH_FALLBACK;
    *o = d->last_off;
    return 0;
}

/* The new id of written place k[0] (delta k[1], old id k[2]), cached as th_group caches; -(reason) on
 * failure. */
static int64_t th_add(th_part *p, const uint32_t *k) {
    nd_search *d = p->d;
    int64_t v = -1;
    if (!d->adds_uncached) {
        v = vm_get(&d->adds, k);
        nd_judge(&d->adds_looks, &d->adds_misses, &d->adds_uncached, d->uncache_after, v < 0);
        if (v >= 0) return v;
    }
    p->computed++;
    v = gen_add(p->gen, k[0], k[1], k[2]);
    if (v < 0) return -TH_FALLBACK;
    if (!d->adds_uncached && vm_put(&d->adds, k, v) != 0) return -TH_NO_MEMORY;
    return v;
}

/* Pack the K values v as a record of store st into r (room for 4 K bytes), widening a field a value does
 * not fit: 0, 1 if the store was widened (records packed before are to be packed again), -1 without memory. */
static int th_pack(cs_store *st, const uint32_t *v, int K, uint8_t *r) {
    int widened = 0;
    for (int f = 0; f < K; f++)
        if (!cs_put(r + st->off[f], st->w[f], v[f])) {
            if (cs_widen_field(st, f, v[f] > 0xFFFFu ? 4 : 2) != 0) return -1;
            widened = 1;
            f = -1;  /* the fields before f moved: all of them again */
        }
    return widened;
}

/* Store record r (hash hh) in part p, found by the arc `src` with binding element be: its reference, or
 * TH_OPEN without memory. */
static uint32_t th_store(th_part *p, const uint8_t *r, uint64_t hh, uint32_t src, uint32_t be) {
    int32_t id;
    int rc = cs_add_hashed(p->st, r, hh, &id);
    uint64_t N = (uint64_t)p->h->N;
    if (rc < 0 || (uint64_t)id * N + N > TH_OPEN) return TH_OPEN;
    if (rc == 1) {
        if (th_push(&p->parent, 1) || th_push(&p->parent_be, 1)) return TH_OPEN;
        p->parent.v[p->parent.n++] = src;
        p->parent_be.v[p->parent_be.n++] = be;
    }
    return (uint32_t)((uint64_t)id * N + (uint64_t)p->me);
}

/* Expand local state i of part p (phase A); 0, or why the search must stop. */
static int th_expand(th_part *p, int64_t i, int64_t *goff) {
    th_search *h = p->h;
    nd_search *d = p->d;
    cs_store *st = p->st;
    int K = h->K, N = h->N, me = p->me;
    uint32_t *s = d->s;
    const uint8_t *rec = st->arena + i * st->W;
    for (int f = 0; f < K; f++) s[f] = (uint32_t)cs_get(rec + st->off[f], st->w[f]);
    int64_t nadd = 0, narcs = 0;
    d->ntmp = 0;
    /* every group's entry for this state, and the new ids of the places its bindings write */
    for (int g = 0; g < d->G; g++) {
        int nr = d->nread[g], nw = d->nwrite[g];
        uint32_t *key = d->req_key;
        for (int r = 0; r < nr; r++) key[r] = s[d->read[g][r]];
        int64_t o;
        int rc = th_group(p, g, key, &o);
        if (rc) return rc;
        goff[g] = o;
        const int32_t *res = d->in_tmp[g] ? d->tmp : d->res;
        int64_t cnt = res[o];
        narcs += cnt;
        if (!nw) continue;
        if (grow((void **)&d->addv, &d->addv_cap, nadd + cnt * nw, 4) != 0) return TH_NO_MEMORY;
        const int32_t *e = res + o + 1;
        for (int64_t j = 0; j < cnt; j++, e += 1 + nr + nw)
            for (int w = 0; w < nw; w++) {
                uint32_t k[3] = {(uint32_t)d->write[g][w], (uint32_t)e[1 + nr + w], s[d->write[g][w]]};
                int64_t v = th_add(p, k);
                if (v < 0) return (int)-v;
                d->addv[nadd++] = (uint32_t)v;
            }
    }
    /* the successors in group order and each group's binding order: their owners (the state's hash sum
     * plus the changes), those of other threads sent (their place ids, source, binding element, arc) */
    if (th_push(&p->dst, narcs) || th_push(&p->bes, narcs) || th_push(&p->aend, 2) || th_push(&p->own, narcs))
        return TH_NO_MEMORY;
    const uint64_t *mul = h->mul;
    uint64_t sum = 0;
    for (int f = 0; f < K; f++) sum += s[f] * mul[f];
    uint32_t src = (uint32_t)(i * N + me);
    int64_t base = p->dst.n, k = 0, nlocal = 0;
    const uint32_t *addv = d->addv;
    for (int g = 0; g < d->G; g++) {
        int nr = d->nread[g], nw = d->nwrite[g];
        const int *rd = d->read[g], *wr = d->write[g];
        const int32_t *res = d->in_tmp[g] ? d->tmp : d->res;
        int64_t cnt = res[goff[g]];
        const int32_t *e = res + goff[g] + 1;
        for (int64_t j = 0; j < cnt; j++, e += 1 + nr + nw, addv += nw, k++) {
            uint64_t x = sum;
            for (int r = 0; r < nr; r++) x += ((uint64_t)(uint32_t)e[1 + r] - s[rd[r]]) * mul[rd[r]];
            for (int w = 0; w < nw; w++) x += ((uint64_t)addv[w] - s[wr[w]]) * mul[wr[w]];
            int o = th_mix_owner(x, N);
            p->own.v[k] = (uint32_t)o;
            p->bes.v[base + k] = (uint32_t)e[0];
            if ((uint32_t)e[0] > p->be_max) p->be_max = (uint32_t)e[0];
            if (o == me) { nlocal++; continue; }
            th_buf *b = &p->out[o];
            if (th_push(b, K + 4)) return TH_NO_MEMORY;
            uint32_t *m = b->v + b->n;
            memcpy(m, s, (size_t)K * 4);
            for (int r = 0; r < nr; r++) m[rd[r]] = (uint32_t)e[1 + r];
            for (int w = 0; w < nw; w++) m[wr[w]] = addv[w];
            int64_t pos = base + k;
            m[K] = src; m[K + 1] = (uint32_t)e[0]; m[K + 2] = (uint32_t)pos; m[K + 3] = (uint32_t)(pos >> 32);
            b->n += K + 4;
            p->dst.v[pos] = TH_OPEN;
        }
    }
    /* the records of those this thread owns: the state's record with the changed fields put in (a value
     * too wide for its field widens the store, and the records are made again), hashed, their table
     * slots prefetched, then stored in order (as nd_run does) */
    int W = st->W;
    for (int widened = nlocal > 0; widened;) {
        widened = 0;
        W = st->W;
        if (grow((void **)&d->recs, &d->recs_cap, narcs * W + 1, 1) || grow((void **)&d->hs, &d->hs_cap, narcs + 1, 8))
            return TH_NO_MEMORY;
        for (int f = 0; f < K; f++) cs_put(d->rs + st->off[f], st->w[f], s[f]);  /* s fits: it is stored here */
        addv = d->addv;
        k = 0;
        for (int g = 0; g < d->G && !widened; g++) {
            int nr = d->nread[g], nw = d->nwrite[g];
            const int *rd = d->read[g], *wr = d->write[g];
            const int32_t *res = d->in_tmp[g] ? d->tmp : d->res;
            int64_t cnt = res[goff[g]];
            const int32_t *e = res + goff[g] + 1;
            for (int64_t j = 0; j < cnt && !widened; j++, e += 1 + nr + nw, addv += nw, k++) {
                if ((int)p->own.v[k] != me) continue;
                uint8_t *r = d->recs + k * W;
                memcpy(r, d->rs, (size_t)W);
                int f = -1;
                uint32_t v = 0;
                for (int q = 0; q < nr && f < 0; q++)
                    if (!cs_put(r + st->off[rd[q]], st->w[rd[q]], (uint32_t)e[1 + q])) { f = rd[q]; v = (uint32_t)e[1 + q]; }
                for (int q = 0; q < nw && f < 0; q++)
                    if (!cs_put(r + st->off[wr[q]], st->w[wr[q]], addv[q])) { f = wr[q]; v = addv[q]; }
                if (f >= 0) {
                    if (cs_widen_field(st, f, v > 0xFFFFu ? 4 : 2) != 0) return TH_NO_MEMORY;
                    widened = 1;
                }
            }
        }
    }
    for (k = 0; k < narcs; k++)
        if ((int)p->own.v[k] == me) {
            d->hs[k] = cs_hash(d->recs + k * W, W);
            __builtin_prefetch(cs_probe_start(st, d->hs[k]));
        }
    for (k = 0; k < narcs && nlocal; k++)
        if ((int)p->own.v[k] == me
            && (p->dst.v[base + k] = th_store(p, d->recs + k * W, d->hs[k], src, p->bes.v[base + k])) == TH_OPEN)
            return TH_NO_MEMORY;
    p->dst.n = p->bes.n = base + narcs;
    memcpy(p->aend.v + p->aend.n, &p->dst.n, 8);
    p->aend.n += 2;
    return 0;
}

#define TH_CHUNK 32  /* successors received packed and prefetched at a time */

/* Store the successors the other threads sent to part p (phase B); 0 or TH_NO_MEMORY. */
static int th_receive(th_part *p) {
    th_search *h = p->h;
    nd_search *d = p->d;
    cs_store *st = p->st;
    int K = h->K, N = h->N, me = p->me, E = K + 4;
    if (grow((void **)&d->recs, &d->recs_cap, TH_CHUNK * 4 * (int64_t)K, 1) || grow((void **)&d->hs, &d->hs_cap, TH_CHUNK, 8))
        return TH_NO_MEMORY;
    for (int from = 0; from < N; from++) {
        th_part *q = &h->parts[from];
        th_buf *b = &q->out[me];
        int64_t n = b->n / E;
        for (int64_t x0 = 0; x0 < n; x0 += TH_CHUNK) {
            int64_t m = n - x0 < TH_CHUNK ? n - x0 : TH_CHUNK;
            int W, rc;
            do {
                W = st->W;
                rc = 0;
                for (int64_t k = 0; k < m && !rc; k++) rc = th_pack(st, b->v + (x0 + k) * E, K, d->recs + k * W);
                if (rc < 0) return TH_NO_MEMORY;
            } while (rc);
            for (int64_t k = 0; k < m; k++) {
                d->hs[k] = cs_hash(d->recs + k * W, W);
                __builtin_prefetch(cs_probe_start(st, d->hs[k]));
            }
            for (int64_t k = 0; k < m; k++) {
                const uint32_t *e = b->v + (x0 + k) * E;
                uint32_t ref = th_store(p, d->recs + k * W, d->hs[k], e[K], e[K + 1]);
                if (ref == TH_OPEN) return TH_NO_MEMORY;
                q->dst.v[(int64_t)e[K + 2] | ((int64_t)e[K + 3] << 32)] = ref;
            }
        }
    }
    return 0;
}

static void th_publish(th_part *p) {
    int64_t pending = 0;
    for (int o = 0; o < p->h->N; o++) pending += p->out[o].n / (p->h->K + 4);
    __atomic_store_n(&p->pub_states, cs_count(p->st), __ATOMIC_RELAXED);
    __atomic_store_n(&p->pub_arcs, p->dst.n, __ATOMIC_RELAXED);
    __atomic_store_n(&p->pub_pending, pending, __ATOMIC_RELAXED);
}

/* The states (stored, and sent but not yet stored: at most that many new ones) and arcs of all parts. */
static void th_totals(th_search *h, int64_t *states, int64_t *arcs) {
    int64_t s = 0, a = 0;
    for (int q = 0; q < h->N; q++) {
        s += __atomic_load_n(&h->parts[q].pub_states, __ATOMIC_RELAXED)
             + __atomic_load_n(&h->parts[q].pub_pending, __ATOMIC_RELAXED);
        a += __atomic_load_n(&h->parts[q].pub_arcs, __ATOMIC_RELAXED);
    }
    *states = s; *arcs = a;
}

static int th_level_mark(th_part *p, int64_t at) {
    if (!p->lv) {
        p->lv_cap = 64;
        if (!(p->lv = (int64_t *)malloc(8 * (size_t)p->lv_cap))) return -1;
    }
    if (grow((void **)&p->lv, &p->lv_cap, p->nlv + 1, 8)) return -1;
    p->lv[p->nlv++] = at;
    return 0;
}

static double th_now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double th_cpu(void) {
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void th_barrier(th_part *p) {
    double t = th_now();
    pthread_barrier_wait(&p->h->bar);
    p->wait += th_now() - t;
}

static void *th_main(void *arg) {
    th_part *p = (th_part *)arg;
    th_search *h = p->h;
    int N = h->N;
    int64_t *goff = (int64_t *)malloc(sizeof(int64_t) * (size_t)(p->d->G + 1));
    if (!goff) th_set_stop(h, TH_NO_MEMORY);
    for (;;) {
        for (int o = 0; o < N; o++) p->out[o].n = 0;
        th_publish(p);
        /* phase A: the states of this level, until a limit (the successors sent count as states: the
         * round ends early so that they are stored and counted exactly before going on) */
        int since = TH_CHECK_EVERY;
        double c0 = th_cpu();
        while (goff && p->head < p->end) {
            if (++since >= TH_CHECK_EVERY) {
                since = 0;
                th_publish(p);
                if (__atomic_load_n(&h->stop, __ATOMIC_RELAXED)) break;
                int64_t s, a;
                th_totals(h, &s, &a);
                if (a >= h->max_arcs) { th_set_stop(h, ND_MAX_ARCS); break; }
                if (s >= h->max_states) break;
            }
            int rc = th_expand(p, p->head, goff);
            if (rc) {  /* the state stays unexpanded: its arcs so far are dropped */
                th_set_stop(h, rc);
                p->dst.n = p->bes.n = (p->aend.n ? ((int64_t *)p->aend.v)[p->aend.n / 2 - 1] : 0);
                break;
            }
            p->head++;
        }
        double c1 = th_cpu();
        p->cpu_a += c1 - c0;
        th_barrier(p);
        /* phase B */
        c0 = th_cpu();
        if (th_receive(p)) th_set_stop(h, TH_NO_MEMORY);
        p->cpu_b += th_cpu() - c0;
        p->stored = cs_count(p->st);  /* (pub_states changes during the next phase A: not read below) */
        p->nnew = p->stored - p->end;
        p->level_done = p->head == p->end;
        p->saw_stop = __atomic_load_n(&h->stop, __ATOMIC_SEQ_CST) != 0;
        th_publish(p);
        th_barrier(p);
        /* every thread reads the same figures here and takes the same decision */
        int64_t fresh = 0, states = 0;
        int stop = 0, done = 1;
        for (int q = 0; q < N; q++) {
            th_part *o = &h->parts[q];
            fresh += o->nnew; states += o->stored; stop |= o->saw_stop; done &= o->level_done;
        }
        if (stop) break;
        if (states >= h->max_states) { th_set_stop(h, ND_MAX_STATES); break; }
        if (!done) continue;  /* a round cut short near the states limit: the level goes on */
        if (!fresh) { th_set_stop(h, TH_COMPLETE); break; }  /* (a stop asked for from now on is too late) */
        if (th_level_mark(p, p->end)) th_set_stop(h, TH_NO_MEMORY);  /* seen by all at the next round */
        p->end = cs_count(p->st);
        if (p->me == 0) __atomic_add_fetch(&h->levels, 1, __ATOMIC_RELAXED);
    }
    free(goff);
    pthread_mutex_lock(&h->done_lock);
    if (--h->running == 0) pthread_cond_broadcast(&h->done_cond);
    pthread_mutex_unlock(&h->done_lock);
    return NULL;
}

void th_free(th_search *h);

/* A search of K-field states with the group layout of nd_new, over n threads, with the net's C `gen`
 * (its tables shared by the threads until th_wait sees them end, or th_free); the stores' fields start
 * `widths` bytes wide (the initial state's), widened as values need it; each thread's caches judge their
 * hit rate after `uncache_after` look-ups (nd_set_uncache_after). */
th_search *th_new(int n, int K, int G, const int32_t *nread, const int32_t *nwrite, const int32_t *fields,
                  void *gen, const uint32_t *s0, const uint8_t *widths, int64_t max_states, int64_t max_arcs,
                  int64_t uncache_after) {
    th_search *h = (th_search *)calloc(1, sizeof(th_search));
    if (!h) return NULL;
    h->N = n; h->K = K; h->gen = gen; h->max_states = max_states; h->max_arcs = max_arcs;
    pthread_mutex_init(&h->done_lock, NULL);
    pthread_cond_init(&h->done_cond, NULL);
    h->parts = (th_part *)calloc((size_t)n, sizeof(th_part));
    h->mul = (uint64_t *)malloc(8 * (size_t)(K + 1));
    if (!h->parts || !h->mul) { th_free(h); return NULL; }
    for (int f = 0; f < K; f++) {  /* splitmix64 of f + 1, made odd */
        uint64_t z = ((uint64_t)f + 1) * 0x9E3779B97F4A7C15ULL;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
        h->mul[f] = (z ^ (z >> 31)) | 1;
    }
    for (int q = 0; q < n; q++) {
        th_part *p = &h->parts[q];
        p->h = h; p->me = q;
        p->st = cs_new(K, widths);
        p->d = nd_new(p->st, K, G, nread, nwrite, fields);
        p->out = (th_buf *)calloc((size_t)n, sizeof(th_buf));
        p->gen = gen_clone(gen);
        if (!p->st || !p->d || !p->out || !p->gen || th_level_mark(p, 0)) { th_free(h); return NULL; }
        nd_set_uncache_after(p->d, uncache_after);
    }
    th_part *own = &h->parts[th_owner(h, s0)];
    uint8_t *r = own->d->recs;  /* room for 4096 bytes (nd_new) */
    if (4 * K > 4096 || th_pack(own->st, s0, K, r) < 0
        || th_store(own, r, cs_hash(r, own->st->W), TH_OPEN, TH_OPEN) == TH_OPEN) { th_free(h); return NULL; }
    for (int q = 0; q < n; q++) { h->parts[q].end = cs_count(h->parts[q].st); th_publish(&h->parts[q]); }
    return h;
}

/* The threads' contexts of the net's C freed: its tables are the caller's alone again. */
static void th_end_sharing(th_search *h) {
    if (!h->parts) return;
    int shared = 0;
    for (int q = 0; q < h->N; q++)
        if (h->parts[q].gen) { gen_free(h->parts[q].gen); h->parts[q].gen = NULL; shared = 1; }
    if (shared) gen_unshare(h->gen);
}

/* Start the threads (0, or -1 if they could not be started). */
int th_start(th_search *h) {
    if (pthread_barrier_init(&h->bar, NULL, (unsigned)h->N) != 0) return -1;
    h->started = 1;
    h->running = h->N;
    for (int q = 0; q < h->N; q++)
        if (pthread_create(&h->parts[q].tid, NULL, th_main, &h->parts[q]) != 0) {
            /* the threads started wait at the first barrier for ever: this cannot be undone */
            h->running -= h->N - q;
            return q ? -2 : -1;
        }
    return 0;
}

/* Wait at most `ms` milliseconds for the search to end: TH_RUNNING, or why it ended (ND_DONE,
 * ND_MAX_STATES, ND_MAX_ARCS, TH_STOPPED, TH_FALLBACK, TH_NO_MEMORY). */
int th_wait(th_search *h, int ms) {
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    ts.tv_sec += ms / 1000;
    ts.tv_nsec += (long)(ms % 1000) * 1000000L;
    if (ts.tv_nsec >= 1000000000L) { ts.tv_sec++; ts.tv_nsec -= 1000000000L; }
    pthread_mutex_lock(&h->done_lock);
    while (h->running > 0)
        if (pthread_cond_timedwait(&h->done_cond, &h->done_lock, &ts) != 0) break;
    int running = h->running;
    pthread_mutex_unlock(&h->done_lock);
    if (running > 0) return TH_RUNNING;
    if (!h->joined) {
        for (int q = 0; q < h->N; q++) pthread_join(h->parts[q].tid, NULL);
        h->joined = 1;
        th_end_sharing(h);
    }
    return h->stop == TH_COMPLETE ? ND_DONE : h->stop;
}

/* Ask the threads to stop (they finish the level's exchange first). */
void th_request_stop(th_search *h) { th_set_stop(h, TH_STOPPED); }

/* states: stored (and on their way); arcs; expanded: the states expanded so far. */
void th_progress(th_search *h, int64_t *out) {
    th_totals(h, &out[0], &out[1]);
    int64_t e = 0;
    for (int q = 0; q < h->N; q++) e += __atomic_load_n(&h->parts[q].head, __ATOMIC_RELAXED);
    out[2] = e;
    out[3] = h->levels;
}

/* After the search: [0] states, [1] expanded states, [2] arcs, [3] the largest binding element,
 * [4] levels, then per thread: its states, the results it computed with the net's C, the microseconds it
 * waited at the barriers, the caches it stopped filling (their results computed anew each time), the
 * microseconds of CPU it spent expanding states and storing the states it was sent. */
void th_sizes(th_search *h, int64_t *out) {
    int64_t n = 0, e = 0, a = 0, be = 0;
    for (int q = 0; q < h->N; q++) {
        th_part *p = &h->parts[q];
        n += cs_count(p->st); e += p->head; a += p->dst.n;
        if ((int64_t)p->be_max > be) be = p->be_max;
        out[5 + q] = cs_count(p->st);
        out[5 + h->N + q] = p->computed;
        out[5 + 2 * h->N + q] = (int64_t)(p->wait * 1e6);
        out[5 + 3 * h->N + q] = nd_uncached(p->d);
        out[5 + 4 * h->N + q] = (int64_t)(p->cpu_a * 1e6);
        out[5 + 5 * h->N + q] = (int64_t)(p->cpu_b * 1e6);
    }
    out[0] = n; out[1] = e; out[2] = a; out[3] = be; out[4] = h->levels;
}

/* The fields' widths of the assembled store (`out`, K bytes): each the widest of the parts', to which every
 * part is widened (0, or -1 without memory). */
int th_widths(th_search *h, uint8_t *out) {
    for (int f = 0; f < h->K; f++) {
        out[f] = 1;
        for (int q = 0; q < h->N; q++) if (h->parts[q].st->w[f] > out[f]) out[f] = h->parts[q].st->w[f];
    }
    for (int q = 0; q < h->N; q++)
        if (memcmp(h->parts[q].st->w, out, (size_t)h->K) != 0 && cs_widen(h->parts[q].st, out) != 0) return -1;
    return 0;
}

/* The one graph: `store` gets every state in the global order, appended without its table (built when
 * first needed: cs_append); offsets[expanded + 1], dst[arcs], bes[arcs] (uint16 if be16, else int32),
 * parent[states] and parent_be[states] are written. 0, -1 (no memory) or -2 (an arc left open: a bug).
 * A state's reference local id * N + part indexes `gid`, its global id. */
int th_assemble(th_search *h, cs_store *store, int64_t *offsets, int32_t *dst, void *bes, int be16,
                int32_t *parent, int32_t *parent_be) {
    int N = h->N;
    int64_t levels = 0, most = 0;
    for (int q = 0; q < N; q++) {
        th_part *p = &h->parts[q];
        /* the boundaries of the last two levels: the current one (partly expanded) and the next */
        if (th_level_mark(p, p->end) || th_level_mark(p, cs_count(p->st))) return -1;
        if (p->nlv - 1 > levels) levels = p->nlv - 1;
        if (cs_count(p->st) > most) most = cs_count(p->st);
    }
    uint32_t *gid = (uint32_t *)malloc(4 * (size_t)((most + 1) * N));
    if (!gid) return -1;
    cs_clear(store);
    int rc = 0;
    /* the order: the expanded states by (level, part, local id), then the others the same way */
    int64_t next = 0, e = 0;
    for (int done = 1; done >= 0 && !rc; done--)
        for (int64_t l = 0; l < levels && !rc; l++)
            for (int q = 0; q < N && !rc; q++) {
                th_part *p = &h->parts[q];
                if (l + 1 >= p->nlv) continue;
                int64_t lo = p->lv[l], hi = p->lv[l + 1];
                if (done) { if (hi > p->head) hi = p->head; }
                else if (lo < p->head) lo = p->head;
                if (lo >= hi) continue;
                for (int64_t i = lo; i < hi; i++) gid[i * N + q] = (uint32_t)next++;
                if (cs_append(store, cs_arena(p->st) + lo * cs_width(p->st), hi - lo) != 0) { rc = -1; break; }
                for (int64_t i = lo; i < hi; i++) {
                    uint32_t r = p->parent.v[i], g = gid[i * N + q];
                    parent[g] = r == TH_OPEN ? -1 : (int32_t)gid[r];
                    parent_be[g] = r == TH_OPEN ? -1 : (int32_t)p->parent_be.v[i];
                }
                if (!done) continue;
                /* the arcs of these expanded states, in order */
                const int64_t *aend = (const int64_t *)p->aend.v;
                for (int64_t i = lo; i < hi; i++) {
                    int64_t a = i ? aend[i - 1] : 0, b = aend[i];
                    if (be16) for (int64_t k = a; k < b; k++) ((uint16_t *)bes)[e + k - a] = (uint16_t)p->bes.v[k];
                    else for (int64_t k = a; k < b; k++) ((int32_t *)bes)[e + k - a] = (int32_t)p->bes.v[k];
                    e += b - a;
                    offsets[gid[i * N + q] + 1] = e;
                }
            }
    /* destinations: every state is numbered now */
    if (!rc) {
        offsets[0] = 0;
        for (int q = 0; q < N && !rc; q++) {
            th_part *p = &h->parts[q];
            const int64_t *aend = (const int64_t *)p->aend.v;
            for (int64_t i = 0; i < p->head && !rc; i++) {
                int64_t a = i ? aend[i - 1] : 0, b = aend[i];
                int32_t *out = dst + offsets[gid[i * N + q]];
                for (int64_t k = a; k < b; k++) {
                    uint32_t r = p->dst.v[k];
                    if (r == TH_OPEN) { rc = -2; break; }
                    *out++ = (int32_t)gid[r];
                }
            }
        }
    }
    free(gid);
    return rc;
}

void th_free(th_search *h) {
    if (!h) return;
    if (h->started && !h->joined) return;  /* threads still running: leak rather than free under them */
    th_end_sharing(h);
    if (h->parts)
        for (int q = 0; q < h->N; q++) {
            th_part *p = &h->parts[q];
            nd_free(p->d); cs_free(p->st);
            free(p->parent.v); free(p->parent_be.v); free(p->lv); free(p->aend.v); free(p->dst.v); free(p->bes.v);
            free(p->own.v);
            if (p->out) for (int o = 0; o < h->N; o++) free(p->out[o].v);
            free(p->out);
        }
    if (h->started) pthread_barrier_destroy(&h->bar);
    pthread_mutex_destroy(&h->done_lock);
    pthread_cond_destroy(&h->done_cond);
    free(h->parts); free(h->mul); free(h); 
}
