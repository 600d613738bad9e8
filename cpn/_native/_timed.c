/* The native search of nets whose enabled binding elements are selected over all transitions at once:
 * timed nets (a binding element occurs at the earliest time any is enabled, at or after the clock) and
 * nets with priorities (only the smallest priority among the enabled ones occurs). Compiled after
 * _search.c, whose search (store, BFS position, batch buffers, transition groups, adds cache) it drives.
 *
 * Per transition group g, two caches:
 *  - ready[g]: read values -> the group's enabled binding elements in the engine's order, each as (ready
 *    time, priority): the earliest model time its tokens are all ready (INT64_MIN: no timed token), and
 *    its priority;
 *  - eff[g]: read values + occurrence time f (0 for a group whose effects do not depend on it) -> the
 *    entries of the binding elements ready at f, in nd_put_group's format (binding element, new value of
 *    each read field, delta id of each written field or ND_NONE for no token).
 * and shifts: (place, id, f) -> the id of the place's marking with every timestamp moved back by f (time
 * condensation). A state of a timed net has the clock as its last field.
 *
 * With the generated C, a group whose results are rarely reused (more than half of its first
 * `uncache_after` lookups in a cache missed, as _search.c judges its groups: a transition reading a place
 * whose marking is new in nearly every state) has them computed anew for each state into scratch
 * buffers instead of being cached (its ready lists and its effects judged apart); the generated C gives
 * the same ids for the same values every time.
 *
 * A state is expanded as the engine's timed successor function does: f is the clock if a binding element
 * is ready then, else the earliest ready time; the binding elements ready at f occur (in group order),
 * written places get add(p, delta, old), the timed places are shifted by f under time condensation, and
 * the clock becomes f (0 under condensation); with priorities only the smallest priority is kept. Where a
 * value is missing from a cache, nt_run returns ND_NEED with the state (request 2, the K fields, then the
 * number and the indexes of the groups whose ready list is missing): the engine computes the whole state in
 * its own order, fills the caches with what it used, and the state is expanded again. */

#include "_timed.h"

#define ND_LEVEL 7
#define ND_NONE 0xFFFFFFFFu
#define NT_AHEAD 16          /* nt_level_fresh: the states hashed, and their slots prefetched, at once */

/* As grow, from a capacity that may be 0. */
static int grow0(void **buf, int64_t *cap, int64_t need, size_t size) {
    if (need <= *cap) return 0;
    int64_t c = *cap ? *cap : 64;
    while (c < need) c *= 2;
    void *b = realloc(*buf, (size_t)c * size);
    if (!b) return -1;
    *buf = b; *cap = c;
    return 0;
}

struct nt_search {
    nd_search *d;
    int G, K;                /* d's groups and fields (d may be freed first) */
    int clock, condense, prio, watch;
    int *timed_g;
    int ntp;
    int *tplaces;
    vmap *ready, *eff;
    int64_t *rdy; int64_t nrdy, rdy_cap;
    vmap shifts;
    uint32_t *succ; int64_t succ_cap;
    int32_t *sbe; int64_t sbe_cap;
    int64_t *sprio; int64_t sprio_cap;
    int64_t *roff;
    uint32_t *ekey;
    uint32_t *miss; int nmiss;   /* the groups whose ready list the state being expanded misses */
    int64_t level_start;
    /* results computed anew (see above): per group, whether its ready lists, its effects are; whether this
     * state's are in the scratch buffers; the judging's counts; the scratch buffers of one state */
    int scratch;             /* nt_put_ready and nt_put_effect write to the scratch buffers */
    int64_t last_rdy, last_eff;  /* where they put (or found) the last ready list, effects */
    uint8_t *r_unc, *e_unc, *r_in_s, *e_in_s;
    int64_t *r_looks, *r_misses, *e_looks, *e_misses, *eoff;
    int64_t *srdy; int64_t nsrdy, srdy_cap;
    int32_t *sres; int64_t nsres, sres_cap;
    /* the time-growth watch's view of a level (nt_level_fresh): per timed place, the id of each marking's
     * untimed view (given by the engine), and the untimed markings met so far (records of U 4-byte fields
     * in a packed store: one hash and, through its slots' tags, mostly one record compared per look-up) */
    int32_t **vid; int64_t *nvid, *vid_cap;
    cs_store *untimed;
    int64_t *fresh; int64_t fresh_cap;
    uint8_t *ukeys;
    uint64_t *uhash;
};

nt_search *nt_new(nd_search *d, int clock, int condense, int prio, const int32_t *timed_g, int ntp,
                  const int32_t *tplaces) {
    nt_search *t = (nt_search *)calloc(1, sizeof(nt_search));
    if (!t) return NULL;
    int G = d->G;
    t->d = d; t->G = G; t->K = d->K; t->clock = clock; t->condense = condense; t->prio = prio;
    t->timed_g = (int *)calloc((size_t)G + 1, sizeof(int));
    t->tplaces = (int *)calloc((size_t)ntp + 1, sizeof(int));
    t->ready = (vmap *)calloc((size_t)G + 1, sizeof(vmap));
    t->eff = (vmap *)calloc((size_t)G + 1, sizeof(vmap));
    t->roff = (int64_t *)calloc((size_t)G + 1, sizeof(int64_t));
    t->ekey = (uint32_t *)calloc((size_t)d->K + 2, 4);
    t->miss = (uint32_t *)calloc((size_t)G + 1, 4);
    t->rdy_cap = 1024; t->rdy = (int64_t *)malloc((size_t)t->rdy_cap * 8);
    t->succ_cap = 1024; t->succ = (uint32_t *)malloc((size_t)t->succ_cap * 4);
    t->sbe_cap = 64; t->sbe = (int32_t *)malloc((size_t)t->sbe_cap * 4);
    t->sprio_cap = 64; t->sprio = (int64_t *)malloc((size_t)t->sprio_cap * 8);
    if (!t->timed_g || !t->tplaces || !t->ready || !t->eff || !t->roff || !t->ekey || !t->miss || !t->rdy || !t->succ
        || !t->sbe || !t->sprio) return NULL;
    t->ntp = ntp;
    for (int i = 0; i < ntp; i++) t->tplaces[i] = tplaces[i];
    for (int g = 0; g < G; g++) {
        t->timed_g[g] = timed_g[g];
        if (vm_init(&t->ready[g], d->nread[g]) != 0 || vm_init(&t->eff[g], d->nread[g] + 1) != 0) return NULL;
    }
    if (vm_init(&t->shifts, 3) != 0) return NULL;
    t->vid = (int32_t **)calloc((size_t)d->K + 1, sizeof(int32_t *));
    t->nvid = (int64_t *)calloc((size_t)d->K + 1, sizeof(int64_t));
    t->vid_cap = (int64_t *)calloc((size_t)d->K + 1, sizeof(int64_t));
    t->ukeys = (uint8_t *)calloc((size_t)NT_AHEAD * ((size_t)d->K + 1), 4);
    t->uhash = (uint64_t *)calloc(NT_AHEAD, 8);
    t->fresh_cap = 64; t->fresh = (int64_t *)malloc((size_t)t->fresh_cap * 8);
    if (!t->vid || !t->nvid || !t->vid_cap || !t->ukeys || !t->uhash || !t->fresh) return NULL;
    t->r_unc = (uint8_t *)calloc((size_t)G + 1, 1); t->e_unc = (uint8_t *)calloc((size_t)G + 1, 1);
    t->r_in_s = (uint8_t *)calloc((size_t)G + 1, 1); t->e_in_s = (uint8_t *)calloc((size_t)G + 1, 1);
    t->r_looks = (int64_t *)calloc((size_t)G + 1, 8); t->r_misses = (int64_t *)calloc((size_t)G + 1, 8);
    t->e_looks = (int64_t *)calloc((size_t)G + 1, 8); t->e_misses = (int64_t *)calloc((size_t)G + 1, 8);
    t->eoff = (int64_t *)calloc((size_t)G + 1, 8);
    t->srdy_cap = 256; t->srdy = (int64_t *)malloc((size_t)t->srdy_cap * 8);
    t->sres_cap = 256; t->sres = (int32_t *)malloc((size_t)t->sres_cap * 4);
    if (!t->r_unc || !t->e_unc || !t->r_in_s || !t->e_in_s || !t->r_looks || !t->r_misses || !t->e_looks
        || !t->e_misses || !t->eoff || !t->srdy || !t->sres) return NULL;
    return t;
}

void nt_free(nt_search *t) {
    if (!t) return;
    for (int g = 0; g < t->G; g++) { vm_free(&t->ready[g]); vm_free(&t->eff[g]); }
    vm_free(&t->shifts);
    cs_free(t->untimed);
    if (t->vid) for (int p = 0; p <= t->K; p++) free(t->vid[p]);
    free(t->vid); free(t->nvid); free(t->vid_cap); free(t->ukeys); free(t->uhash); free(t->fresh);
    free(t->r_unc); free(t->e_unc); free(t->r_in_s); free(t->e_in_s); free(t->r_looks); free(t->r_misses);
    free(t->e_looks); free(t->e_misses); free(t->eoff); free(t->srdy); free(t->sres);
    free(t->timed_g); free(t->tplaces); free(t->ready); free(t->eff); free(t->roff); free(t->ekey); free(t->miss);
    free(t->rdy); free(t->succ); free(t->sbe); free(t->sprio); free(t);
}

void nt_set_watch(nt_search *t, int watch) { t->watch = watch; }
int64_t nt_level_start(nt_search *t) { return t->level_start; }

/* Group g's binding elements for the read values `key`: n pairs (ready time, priority) (with t->scratch,
 * into the scratch buffer). Where they went: t->last_rdy. */
int nt_put_ready(nt_search *t, int g, const uint32_t *key, int64_t n, const int64_t *pairs) {
    int64_t **buf = t->scratch ? &t->srdy : &t->rdy;
    int64_t *len = t->scratch ? &t->nsrdy : &t->nrdy, *cap = t->scratch ? &t->srdy_cap : &t->rdy_cap;
    if (!t->scratch) {
        int64_t had = vm_get(&t->ready[g], key);
        if (had >= 0) { t->last_rdy = had; return 0; }
    }
    if (grow((void **)buf, cap, *len + 1 + 2 * n, 8) != 0) return -1;
    int64_t off = *len;
    (*buf)[off] = n;
    memcpy(*buf + off + 1, pairs, (size_t)(2 * n) * 8);
    *len += 1 + 2 * n;
    t->last_rdy = off;
    return t->scratch ? 0 : vm_put(&t->ready[g], key, off);
}

/* Group g's entries for the read values and occurrence time `key` (nread + 1 values) (with t->scratch,
 * into the scratch buffer). Where they went: t->last_eff. */
int nt_put_effect(nt_search *t, int g, const uint32_t *key, int64_t n, const int32_t *entries) {
    nd_search *d = t->d;
    int32_t **buf = t->scratch ? &t->sres : &d->res;
    int64_t *len = t->scratch ? &t->nsres : &d->nres, *cap = t->scratch ? &t->sres_cap : &d->res_cap;
    if (!t->scratch) {
        int64_t had = vm_get(&t->eff[g], key);
        if (had >= 0) { t->last_eff = had; return 0; }
    }
    int64_t width = 1 + d->nread[g] + d->nwrite[g];
    if (grow((void **)buf, cap, *len + 1 + n * width, 4) != 0) return -1;
    int64_t off = *len;
    (*buf)[off] = (int32_t)n;
    memcpy(*buf + off + 1, entries, (size_t)(n * width) * 4);
    *len += 1 + n * width;
    t->last_eff = off;
    return t->scratch ? 0 : vm_put(&t->eff[g], key, off);
}

int nt_put_shift(nt_search *t, uint32_t p, uint32_t id, uint32_t f, uint32_t nid) {
    uint32_t k[3] = {p, id, f};
    if (vm_get(&t->shifts, k) >= 0) return 0;
    return vm_put(&t->shifts, k, nid);
}

/* Many values at once, as the engine sends them after expanding a state (0, or -1: no memory):
 * readies: n records (g, count, the group's read values, count x (ready, priority));
 * effects: n records (g, time, count, the group's read values, count entries);
 * adds: n quadruples (p, delta, old, new); shifts: n quadruples (p, id, time, new). */
int nt_put_readies(nt_search *t, const int64_t *buf, int64_t n) {
    uint32_t *key = t->ekey;
    for (int64_t i = 0; i < n; i++) {
        int g = (int)buf[0];
        int64_t cnt = buf[1];
        int nr = t->d->nread[g];
        for (int k = 0; k < nr; k++) key[k] = (uint32_t)buf[2 + k];
        if (nt_put_ready(t, g, key, cnt, buf + 2 + nr) != 0) return -1;
        buf += 2 + nr + 2 * cnt;
    }
    return 0;
}

int nt_put_effects(nt_search *t, const int32_t *buf, int64_t n) {
    uint32_t *key = t->ekey;
    for (int64_t i = 0; i < n; i++) {
        int g = buf[0];
        int64_t cnt = buf[2];
        int nr = t->d->nread[g], nw = t->d->nwrite[g];
        for (int k = 0; k < nr; k++) key[k] = (uint32_t)buf[3 + k];
        key[nr] = (uint32_t)buf[1];
        if (nt_put_effect(t, g, key, cnt, buf + 3 + nr) != 0) return -1;
        buf += 3 + nr + cnt * (1 + nr + nw);
    }
    return 0;
}

int nt_put_adds(nt_search *t, const uint32_t *buf, int64_t n) {
    for (int64_t i = 0; i < n; i++, buf += 4)
        if (nd_put_add(t->d, buf[0], buf[1], buf[2], buf[3]) != 0) return -1;
    return 0;
}

int nt_put_shifts(nt_search *t, const uint32_t *buf, int64_t n) {
    for (int64_t i = 0; i < n; i++, buf += 4)
        if (nt_put_shift(t, buf[0], buf[1], buf[2], buf[3]) != 0) return -1;
    return 0;
}

#ifdef ND_GENERATED
/* compiled after this file (cpn/engine/ccodegen.py, `timed_native_code`): group k's ready list for the
 * read ids `key`, and its effects at time f in state s (each entry's written places' new ids and shifted
 * markings made right after it, in the engine's order), put into the caches; 0, -1: left to the caller
 * (Python), -2: no memory */
static int gen_ready(void *g, nt_search *t, int k, const uint32_t *key);
static int gen_effect(void *g, nt_search *t, int k, const uint32_t *key, int64_t f, const uint32_t *s);
static int64_t gen_shift(void *g, uint32_t p, uint32_t id, uint32_t f);
#endif

/* Successor u of state s by the entry e of group g occurring at time f: the read places' new ids, the
 * written places' (d->adds), the markings shifted by f under time condensation (t->shifts); with the
 * generated C, a value not cached yet is computed and cached. 0, -1: a cache misses a value, -2: no memory. */
static int nt_succ(nt_search *t, int g, const uint32_t *s, int64_t f, const int32_t *e, uint32_t *u) {
    nd_search *d = t->d;
    int K = d->K, nr = d->nread[g], nw = d->nwrite[g];
    memcpy(u, s, (size_t)K * 4);
    for (int i = 0; i < nr; i++) u[d->read[g][i]] = (uint32_t)e[1 + i];
    for (int w = 0; w < nw; w++) {
        uint32_t delta = (uint32_t)e[1 + nr + w];
        if (delta == ND_NONE) continue;
        int p = d->write[g][w];
        uint32_t k3[3] = {(uint32_t)p, delta, u[p]};
        int64_t v = vm_get(&d->adds, k3);
#ifdef ND_GENERATED
        if (v < 0 && d->gen) {
            v = gen_add(d->gen, k3[0], k3[1], k3[2]);
            if (v >= 0 && (v > (int64_t)0xFFFFFFFFu || vm_put(&d->adds, k3, v) != 0)) return -2;
        }
#endif
        if (v < 0) return -1;
        u[p] = (uint32_t)v;
    }
    if (t->condense && f) {
        for (int i = 0; i < t->ntp; i++) {
            int p = t->tplaces[i];
            uint32_t k3[3] = {(uint32_t)p, u[p], (uint32_t)f};
            int64_t v = vm_get(&t->shifts, k3);
#ifdef ND_GENERATED
            if (v < 0 && d->gen) {
                v = gen_shift(d->gen, k3[0], k3[1], k3[2]);
                if (v >= 0 && vm_put(&t->shifts, k3, v) != 0) return -2;
            }
#endif
            if (v < 0) return -1;
            u[p] = (uint32_t)v;
        }
    }
    if (t->clock) u[K - 1] = t->condense ? 0 : (uint32_t)f;
    return 0;
}

#ifdef ND_GENERATED
/* For the generated C: the successor of state s by entry e of group g at time f, its values cached (the
 * successor itself into the scratch state d->t). */
static int nt_settle(nt_search *t, int g, const uint32_t *s, int64_t f, const int32_t *e) {
    return nt_succ(t, g, s, f, e, t->d->t);
}
#endif

static int64_t nt_select(nt_search *t, int64_t m);

/* The successors of state s of an untimed net (with priorities) into t->succ, t->sbe and t->sprio, each
 * group's right after its binding elements, as the engine's order goes (`TimedGroups._untimed`): their
 * number, -1 if a cache misses a value, -2 if memory runs out. */
static int64_t nt_expand_untimed(nt_search *t, const uint32_t *s) {
    nd_search *d = t->d;
    int K = d->K, G = d->G;
    int64_t m = 0;
    int stuck = 0;
    t->nmiss = 0;
    for (int g = 0; g < G; g++) {
        int nr = d->nread[g], nw = d->nwrite[g];
        for (int i = 0; i < nr; i++) t->ekey[i] = s[d->read[g][i]];
        int64_t o = vm_get(&t->ready[g], t->ekey);
#ifdef ND_GENERATED
        if (o < 0 && d->gen && !t->nmiss && !stuck) {
            int rc = gen_ready(d->gen, t, g, t->ekey);
            if (rc == -2) return -2;
            for (int i = 0; i < nr; i++) t->ekey[i] = s[d->read[g][i]];
            if (rc == 0) o = vm_get(&t->ready[g], t->ekey);
        }
#endif
        if (o < 0) { t->miss[t->nmiss++] = (uint32_t)g; continue; }
        if (t->nmiss || stuck) continue;  /* the engine expands the state: the ready lists it misses */
        int64_t cnt = t->rdy[o];
        if (!cnt) continue;
        t->ekey[nr] = 0;
        int64_t eo = vm_get(&t->eff[g], t->ekey);
        if (eo < 0) { stuck = 1; continue; }
        int64_t ec = d->res[eo];
        for (int64_t k = 0; k < ec && !stuck; k++) {
            if (grow((void **)&t->succ, &t->succ_cap, (m + 1) * K, 4) != 0
                || grow((void **)&t->sbe, &t->sbe_cap, m + 1, 4) != 0
                || grow((void **)&t->sprio, &t->sprio_cap, m + 1, 8) != 0) return -2;
            const int32_t *e = d->res + eo + 1 + k * (1 + nr + nw);
            int rc = nt_succ(t, g, s, 0, e, t->succ + m * K);
            if (rc == -2) return rc;
            if (rc) { stuck = 1; break; }
            e = d->res + eo + 1 + k * (1 + nr + nw);
            t->sbe[m] = e[0];
            t->sprio[m] = k < cnt ? t->rdy[o + 2 + 2 * k] : 0;
            m++;
        }
    }
    if (t->nmiss || stuck) return -1;
    return nt_select(t, m);
}

/* The successors of state s into t->succ (K fields each), t->sbe and t->sprio: their number, -1 if a
 * cache misses a value, -2 if memory runs out. */
static int64_t nt_expand(nt_search *t, const uint32_t *s) {
    nd_search *d = t->d;
    int K = d->K, G = d->G;
    if (!t->clock) return nt_expand_untimed(t, s);
    int64_t clock = t->clock ? (int64_t)s[K - 1] : 0;
    int any = 0, now = 0;
    int64_t minr = INT64_MAX;
    t->nmiss = 0;
    t->nsrdy = 0; t->nsres = 0;
    for (int g = 0; g < G; g++) {
        int nr = d->nread[g];
        for (int i = 0; i < nr; i++) t->ekey[i] = s[d->read[g][i]];
        int64_t o = -1;
        t->r_in_s[g] = 0; t->e_in_s[g] = 0;
#ifdef ND_GENERATED
        int tried = 0;
        if (t->r_unc[g] && !t->nmiss) {  /* computed anew (in the groups' order, as the engine: none after a miss) */
            t->scratch = 1;
            int rc = gen_ready(d->gen, t, g, t->ekey);
            t->scratch = 0;
            tried = 1;
            if (rc == -2) return -2;
            for (int i = 0; i < nr; i++) t->ekey[i] = s[d->read[g][i]];
            if (rc == 0) {
                o = t->last_rdy;
                t->r_in_s[g] = 1;
                if (!t->timed_g[g]) { t->eoff[g] = t->last_eff; t->e_in_s[g] = 1; }  /* (put with it) */
            }
        }
        if (o < 0) {
            o = vm_get(&t->ready[g], t->ekey);
            if (d->gen && !tried) nd_judge(&t->r_looks[g], &t->r_misses[g], &t->r_unc[g], d->uncache_after, o < 0);
            if (o < 0 && d->gen && !t->nmiss && !tried) {
                int rc = gen_ready(d->gen, t, g, t->ekey);
                if (rc == -2) return -2;
                for (int i = 0; i < nr; i++) t->ekey[i] = s[d->read[g][i]];
                if (rc == 0) o = t->last_rdy;
            }
        }
#else
        o = vm_get(&t->ready[g], t->ekey);
#endif
        if (o < 0) { t->miss[t->nmiss++] = (uint32_t)g; continue; }
        if (t->nmiss) continue;
        t->roff[g] = o;
        const int64_t *rb = t->r_in_s[g] ? t->srdy : t->rdy;
        int64_t cnt = rb[o];
        for (int64_t j = 0; j < cnt; j++) {
            int64_t r = rb[o + 1 + 2 * j];
            any = 1;
            if (r <= clock) now = 1;
            if (r < minr) minr = r;
        }
    }
    if (t->nmiss) return -1;
    if (!any) return 0;
    int64_t f = now ? clock : minr;
    if (f < 0 || f > (int64_t)0xFFFFFFFFu) return -1;  /* the engine says whether it fits */
    int64_t m = 0;
    for (int g = 0; g < G; g++) {
        int nr = d->nread[g], nw = d->nwrite[g];
        int64_t o = t->roff[g];
        const int64_t *rb = t->r_in_s[g] ? t->srdy : t->rdy;
        int64_t cnt = rb[o];
        int64_t c = 0;
        for (int64_t j = 0; j < cnt; j++) c += rb[o + 1 + 2 * j] <= f;
        if (!c) continue;
        for (int i = 0; i < nr; i++) t->ekey[i] = s[d->read[g][i]];
        t->ekey[nr] = t->timed_g[g] ? (uint32_t)f : 0;
        int64_t eo = -1;
        int in_s = t->e_in_s[g];
        if (in_s) eo = t->eoff[g];
#ifdef ND_GENERATED
        int tried = 0;
        if (eo < 0 && t->e_unc[g]) {
            t->scratch = 1;
            int rc = gen_effect(d->gen, t, g, t->ekey, f, s);
            t->scratch = 0;
            tried = 1;
            if (rc == -2) return -2;
            for (int i = 0; i < nr; i++) t->ekey[i] = s[d->read[g][i]];
            t->ekey[nr] = t->timed_g[g] ? (uint32_t)f : 0;
            if (rc == 0) { eo = t->last_eff; in_s = 1; }
        }
        if (eo < 0) {
            eo = vm_get(&t->eff[g], t->ekey);
            if (d->gen && !tried) nd_judge(&t->e_looks[g], &t->e_misses[g], &t->e_unc[g], d->uncache_after, eo < 0);
            if (eo < 0 && d->gen && !tried) {
                int rc = gen_effect(d->gen, t, g, t->ekey, f, s);
                if (rc == -2) return -2;
                if (rc == 0) eo = t->last_eff;
            }
        }
#else
        eo = vm_get(&t->eff[g], t->ekey);
#endif
        if (eo < 0) return -1;
        int64_t ec = (in_s ? t->sres : d->res)[eo];
        int64_t j = 0;
        for (int64_t k = 0; k < ec; k++) {
            /* (the buffers may grow on the way: the entry is found anew after nt_succ) */
            const int32_t *e = (in_s ? t->sres : d->res) + eo + 1 + k * (1 + nr + nw);
            while (j < cnt && rb[o + 1 + 2 * j] > f) j++;
            int64_t prio = j < cnt ? rb[o + 2 + 2 * j] : 0;
            j++;
            if (grow((void **)&t->succ, &t->succ_cap, (m + 1) * K, 4) != 0
                || grow((void **)&t->sbe, &t->sbe_cap, m + 1, 4) != 0
                || grow((void **)&t->sprio, &t->sprio_cap, m + 1, 8) != 0) return -2;
            int rc = nt_succ(t, g, s, f, e, t->succ + m * K);
            if (rc) return rc;
            e = (in_s ? t->sres : d->res) + eo + 1 + k * (1 + nr + nw);
            t->sbe[m] = e[0];
            t->sprio[m] = prio;
            m++;
        }
    }
    return nt_select(t, m);
}

/* Keep the successors of the smallest priority (with priorities): their number. */
static int64_t nt_select(nt_search *t, int64_t m) {
    int K = t->d->K;
    if (t->prio && m > 1) {
        int64_t best = t->sprio[0];
        for (int64_t i = 1; i < m; i++) if (t->sprio[i] < best) best = t->sprio[i];
        int64_t k = 0;
        for (int64_t i = 0; i < m; i++) {
            if (t->sprio[i] != best) continue;
            if (k != i) {
                memcpy(t->succ + k * K, t->succ + i * K, (size_t)K * 4);
                t->sbe[k] = t->sbe[i];
            }
            k++;
        }
        m = k;
    }
    return m;
}

/* nd_run for these nets: expand states from `head` on; return at `until` (ND_CHECK), at a limit, when the
 * queue is empty, at each new BFS level if asked to (ND_LEVEL: the level is nt_level_start .. the level's
 * end), or when a cache misses a value (ND_NEED: call again once the engine has filled them). */
int nt_run(nt_search *t, int64_t until, int64_t max_states, int64_t max_arcs) {
    nd_search *d = t->d;
    cs_store *st = d->st;
    int K = d->K;
    int status;
    for (;;) {
        int64_t n = st->n;
        if (d->head >= n) { status = ND_DONE; break; }
        if (d->head == d->level_end) {
            d->levels++;
            t->level_start = d->level_end;
            d->level_end = n;
            if (t->watch) { status = ND_LEVEL; break; }
        }
        if (d->head == until) { status = ND_CHECK; break; }
        if (n >= max_states) { status = ND_MAX_STATES; break; }
        if (d->total_arcs >= max_arcs) { status = ND_MAX_ARCS; break; }
        memcpy(d->rs, st->arena + d->head * st->W, (size_t)st->W);
        for (int f = 0; f < K; f++) d->s[f] = (uint32_t)cs_get(d->rs + st->off[f], st->w[f]);
        int64_t m = nt_expand(t, d->s);
        if (m == -2) { status = ND_NO_MEMORY; break; }
        if (m == -1) {
            if (grow((void **)&d->req, &d->req_cap, 2 + K + t->nmiss, 4) != 0) { status = ND_NO_MEMORY; break; }
            d->req[0] = 2;
            memcpy(d->req + 1, d->s, (size_t)K * 4);
            d->req[1 + K] = (uint32_t)t->nmiss;
            memcpy(d->req + 2 + K, t->miss, (size_t)t->nmiss * 4);
            d->nreq = 2 + K + t->nmiss;
            status = ND_NEED;
            break;
        }
        if (!d->be32) {
            int wide = 0;
            for (int64_t i = 0; i < m; i++) if (t->sbe[i] > 65535) wide = 1;
            if (wide) { status = ND_WIDE_BE; break; }
        }
        if (grow((void **)&d->dst, &d->arcs_cap, d->narcs + m, 4) != 0
            || grow(&d->bes, &d->bes_cap, d->narcs + m, 4) != 0
            || grow((void **)&d->offsets, &d->off_cap, d->noff + 1, 8) != 0
            || grow((void **)&d->parent, &d->new_cap, d->nnew + m, 4) != 0
            || grow((void **)&d->parent_be, &d->pbe_cap, d->nnew + m, 4) != 0
            || grow((void **)&d->hs, &d->hs_cap, m, 8) != 0) { status = ND_NO_MEMORY; break; }
        /* the successors' records (a value too wide for its field widens the store's records, and the
         * records are made anew), hashed and their table slots prefetched, then stored in order */
        int failed = 0;
        for (;;) {
            int W = st->W, wf = -1;
            uint32_t wv = 0;
            if (grow((void **)&d->recs, &d->recs_cap, m * W, 1) != 0) { failed = 1; break; }
            for (int64_t i = 0; i < m && wf < 0; i++) {
                const uint32_t *u = t->succ + i * K;
                uint8_t *r = d->recs + i * W;
                for (int f = 0; f < K; f++)
                    if (!cs_put(r + st->off[f], st->w[f], u[f])) { wf = f; wv = u[f]; break; }
            }
            if (wf < 0) break;
            if (cs_widen_field(st, wf, wv > 0xFFFFu ? 4 : 2) != 0) { failed = 1; break; }
        }
        if (failed) { status = ND_NO_MEMORY; break; }
        int W = st->W;
        for (int64_t i = 0; i < m; i++) {
            d->hs[i] = cs_hash(d->recs + i * W, W);
            __builtin_prefetch(cs_probe_start(st, d->hs[i]));
        }
        for (int64_t i = 0; i < m; i++) {
            int32_t id;
            int r = cs_add_hashed(st, d->recs + i * W, d->hs[i], &id);
            if (r < 0) { failed = 1; break; }
            if (r == 1) {
                d->parent[d->nnew] = (int32_t)d->head;
                d->parent_be[d->nnew] = t->sbe[i];
                d->nnew++;
            }
            d->dst[d->narcs] = id;
            if (d->be32) ((int32_t *)d->bes)[d->narcs] = t->sbe[i];
            else ((uint16_t *)d->bes)[d->narcs] = (uint16_t)t->sbe[i];
            d->narcs++;
        }
        if (failed) { status = ND_NO_MEMORY; break; }
        d->total_arcs += m;
        d->offsets[d->noff++] = d->total_arcs;
        d->head++;
    }
    return status;
}

/* The ids of the untimed views of timed place p's markings `from` .. from + n - 1 (0, -1: no memory). */
int nt_put_views(nt_search *t, int p, int64_t from, int64_t n, const int32_t *ids) {
    if (from != t->nvid[p]) return from < t->nvid[p] ? 0 : -1;
    if (grow0((void **)&t->vid[p], &t->vid_cap[p], from + n, 4) != 0) return -1;
    memcpy(t->vid[p] + from, ids, (size_t)n * 4);
    t->nvid[p] = from + n;
    return 0;
}

/* For the time-growth watch, the states start .. end - 1 of a level: the number of them whose untimed
 * marking (the places' markings, a timed place's as its untimed view) the watch has not met before, their
 * indices in nt_fresh, and the smallest and largest clock in *lo, *hi; -1 if a view id is missing (the
 * engine gives it: nt_put_views; the markings met so far are kept), -2 without memory. */
int64_t nt_level_fresh(nt_search *t, int64_t start, int64_t end, int64_t *lo, int64_t *hi) {
    nd_search *d = t->d;
    cs_store *st = d->st;
    int K = d->K, U = t->clock ? K - 1 : K;
    if (!t->untimed) {
        uint8_t w[U ? U : 1];
        for (int f = 0; f < U; f++) w[f] = 4;
        t->untimed = cs_new(U, w);
        if (!t->untimed) return -2;
    }
    cs_store *um = t->untimed;
    int W = um->W;
    int64_t m = 0, a = INT64_MAX, b = INT64_MIN;
    /* NT_AHEAD states at a time: their untimed records made and hashed, their slots prefetched, then
     * looked up in order (a look-up is a likely cache miss) */
    for (int64_t i0 = start; i0 < end; i0 += NT_AHEAD) {
        int64_t n = end - i0 < NT_AHEAD ? end - i0 : NT_AHEAD;
        for (int64_t j = 0; j < n; j++) {
            const uint8_t *r = st->arena + (i0 + j) * st->W;
            uint32_t k[U ? U : 1];
            for (int f = 0; f < U; f++) k[f] = (uint32_t)cs_get(r + st->off[f], st->w[f]);
            for (int q = 0; q < t->ntp; q++) {
                int p = t->tplaces[q];
                if ((int64_t)k[p] >= t->nvid[p]) return -1;
                k[p] = (uint32_t)t->vid[p][k[p]];
            }
            uint8_t *u = t->ukeys + j * W;
            for (int f = 0; f < U; f++) cs_put(u + 4 * f, 4, k[f]);
            t->uhash[j] = cs_hash(u, W);
            __builtin_prefetch(cs_probe_start(um, t->uhash[j]));
            int64_t c = t->clock ? (int64_t)cs_get(r + st->off[K - 1], st->w[K - 1]) : 0;
            if (c < a) a = c;
            if (c > b) b = c;
        }
        for (int64_t j = 0; j < n; j++) {
            int32_t id;
            int rc = cs_add_hashed(um, t->ukeys + j * W, t->uhash[j], &id);
            if (rc < 0) return -2;
            if (rc == 0) continue;
            if (grow((void **)&t->fresh, &t->fresh_cap, m + 1, 8) != 0) return -2;
            t->fresh[m++] = i0 + j;
        }
    }
    *lo = a; *hi = b;
    return m;
}

int64_t *nt_fresh(nt_search *t) { return t->fresh; }

/* How many caches compute their results anew each time (a group's ready lists, its effects). */
int nt_uncached(nt_search *t) {
    int k = 0;
    for (int g = 0; g < t->G; g++) k += t->r_unc[g] + t->e_unc[g];
    return k;
}

int64_t nt_cache_bytes(nt_search *t) {
    int64_t b = t->rdy_cap * 8 + t->shifts.cap * 20 + (int64_t)(t->shifts.mask + 1) * 4
                + t->srdy_cap * 8 + t->sres_cap * 4 + (t->untimed ? cs_nbytes(t->untimed) : 0);
    for (int g = 0; g < t->d->G; g++)
        b += t->ready[g].cap * (t->ready[g].len * 4 + 8) + (int64_t)(t->ready[g].mask + 1) * 4
             + t->eff[g].cap * (t->eff[g].len * 4 + 8) + (int64_t)(t->eff[g].mask + 1) * 4;
    return b;
}
