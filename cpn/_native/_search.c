/* The native breadth-first search over transition groups (compiled after _packed.c, whose store it uses).
 *
 * A state is K fields (the engine's place ids, uint32 while a state is expanded; in the store each field
 * is as narrow as its largest id so far allows, 1, 2 or 4 bytes, widened by the search when an id needs
 * it: cs_widen_field). Transition group g reads the fields read[g] and
 * writes the fields write[g]; its enabled binding elements depend on the read fields only, so its result
 * is cached per tuple of those values: a list of entries (binding element, new value of each read
 * field, delta id of each written field). A written field's new value is add(p, delta, old value),
 * cached per (p, delta, old value). Both caches are filled by the caller (the engine, in Python): the
 * search returns ND_NEED with what the state being expanded misses first (nd_requests: 0, g, the
 * key's values for a group, or the written places of one group's bindings: 1, p, delta, old each) and
 * is called again once it is filled. A state is expanded only once everything it needs is cached, so nothing is stored twice.
 *
 * A state's successors are packed as records and hashed first, their table slots prefetched, then
 * looked up and stored in order (a probe is the search's likeliest cache miss).
 *
 * The search expands states in id order (BFS); arcs, per-state arc offsets and the BFS parents of new
 * states go to batch buffers that the caller empties (nd_clear_batch) between calls.
 */
#include "_search.h"

nd_search *nd_new(cs_store *st, int K, int G, const int32_t *nread, const int32_t *nwrite, const int32_t *fields) {
    nd_search *d = (nd_search *)calloc(1, sizeof(nd_search));
    if (!d) return NULL;
    d->K = K; d->G = G; d->st = st;
    d->nread = (int *)calloc((size_t)G + 1, sizeof(int));
    d->nwrite = (int *)calloc((size_t)G + 1, sizeof(int));
    d->read = (int **)calloc((size_t)G + 1, sizeof(int *));
    d->write = (int **)calloc((size_t)G + 1, sizeof(int *));
    d->groups = (vmap *)calloc((size_t)G + 1, sizeof(vmap));
    int pos = 0;
    for (int g = 0; g < G; g++) {
        d->nread[g] = nread[g]; d->nwrite[g] = nwrite[g];
        d->read[g] = (int *)malloc(sizeof(int) * (size_t)(nread[g] + 1));
        d->write[g] = (int *)malloc(sizeof(int) * (size_t)(nwrite[g] + 1));
        for (int i = 0; i < nread[g]; i++) d->read[g][i] = fields[pos++];
        for (int i = 0; i < nwrite[g]; i++) d->write[g][i] = fields[pos++];
        if (vm_init(&d->groups[g], nread[g]) != 0) return NULL;
    }
    if (vm_init(&d->adds, 3) != 0) return NULL;
    d->res_cap = 1024; d->res = (int32_t *)malloc((size_t)d->res_cap * 4);
    d->arcs_cap = 4096; d->dst = (int32_t *)malloc((size_t)d->arcs_cap * 4); d->bes_cap = 4096; d->bes = malloc((size_t)d->bes_cap * 4);
    d->off_cap = 1024; d->offsets = (int64_t *)malloc((size_t)d->off_cap * 8);
    d->new_cap = 1024; d->parent = (int32_t *)malloc((size_t)d->new_cap * 4);
    d->pbe_cap = 1024; d->parent_be = (int32_t *)malloc((size_t)d->pbe_cap * 4);
    d->req_key = (uint32_t *)malloc(4 * (size_t)(K + 1));
    d->req_cap = 64; d->req = (uint32_t *)malloc(4 * (size_t)d->req_cap);
    d->s = (uint32_t *)malloc(4 * (size_t)(K + 1));
    d->t = (uint32_t *)malloc(4 * (size_t)(K + 1));
    d->addv_cap = 1024; d->addv = (uint32_t *)malloc((size_t)d->addv_cap * 4);
    d->rs = (uint8_t *)malloc(4 * (size_t)(K + 1));
    d->recs_cap = 4096; d->recs = (uint8_t *)malloc((size_t)d->recs_cap);
    d->hs_cap = 256; d->hs = (uint64_t *)malloc((size_t)d->hs_cap * 8);
    d->tmp_cap = 1024; d->tmp = (int32_t *)malloc((size_t)d->tmp_cap * 4);
    d->uncached = (uint8_t *)calloc((size_t)G + 1, 1);
    d->in_tmp = (uint8_t *)calloc((size_t)G + 1, 1);
    d->looks = (int64_t *)calloc((size_t)G + 1, 8);
    d->misses = (int64_t *)calloc((size_t)G + 1, 8);
    d->uncache_after = -1;
    for (int g = 0; g < G; g++) d->looks[g] = -1;  /* not counted until nd_set_uncache_after */
    d->adds_looks = -1;
    d->level_end = 1;
    return d;
}

void nd_free(nd_search *d) {
    if (!d) return;
    for (int g = 0; g < d->G; g++) { free(d->read[g]); free(d->write[g]); vm_free(&d->groups[g]); }
    vm_free(&d->adds);
    free(d->nread); free(d->nwrite); free(d->read); free(d->write); free(d->groups); free(d->res);
    free(d->dst); free(d->bes); free(d->offsets); free(d->parent); free(d->parent_be);
    free(d->req_key); free(d->s); free(d->t); free(d->addv); free(d->req);
    free(d->rs); free(d->recs); free(d->hs);
    free(d->tmp); free(d->uncached); free(d->in_tmp); free(d->looks); free(d->misses); free(d);
}

/* The result of group g for the read values `key`: n entries of 1 + nread + nwrite values. */
int nd_put_group(nd_search *d, int g, const uint32_t *key, int64_t n, const int32_t *entries) {
    int64_t width = 1 + d->nread[g] + d->nwrite[g];
    if (d->scratch) {
        if (grow((void **)&d->tmp, &d->tmp_cap, d->ntmp + 1 + n * width, 4) != 0) return -1;
        d->last_off = d->ntmp;
        d->tmp[d->ntmp] = (int32_t)n;
        memcpy(d->tmp + d->ntmp + 1, entries, (size_t)(n * width) * 4);
        d->ntmp += 1 + n * width;
        return 0;
    }
    int64_t had = vm_get(&d->groups[g], key);
    if (had >= 0) { d->last_off = had; return 0; }
    int64_t need = d->nres + 1 + n * width;
    if (need > d->res_cap) {
        int64_t cap = d->res_cap;
        while (cap < need) cap *= 2;
        int32_t *r = (int32_t *)realloc(d->res, (size_t)cap * 4);
        if (!r) return -1;
        d->res = r; d->res_cap = cap;
    }
    int64_t off = d->nres;
    d->res[off] = (int32_t)n;
    memcpy(d->res + off + 1, entries, (size_t)(n * width) * 4);
    d->nres = need;
    d->last_off = off;
    return vm_put(&d->groups[g], key, off);
}

int nd_put_add(nd_search *d, uint32_t p, uint32_t delta, uint32_t old, uint32_t nid) {
    uint32_t k[3] = {p, delta, old};
    if (vm_get(&d->adds, k) >= 0) return 0;
    return vm_put(&d->adds, k, nid);
}

/* Expand states from `head` on; return at `until` (ND_CHECK), at a limit, when the queue is empty,
 * or when a cache entry is missing (the key is in req_*; call again once it is filled). */
int nd_run(nd_search *d, int64_t until, int64_t max_states, int64_t max_arcs) {
    cs_store *st = d->st;
    int K = d->K;
    int64_t off[256];
    int64_t *goff = d->G <= 256 ? off : (int64_t *)malloc(sizeof(int64_t) * (size_t)d->G);
    int status;
    for (;;) {
        int64_t n = st->n;
        if (d->head >= n) { status = ND_DONE; break; }
        if (d->head == d->level_end) { d->levels++; d->level_end = n; }
        if (d->head == until) { status = ND_CHECK; break; }
        if (n >= max_states) { status = ND_MAX_STATES; break; }
        if (d->total_arcs >= max_arcs) { status = ND_MAX_ARCS; break; }
        uint32_t *s = d->s;
        memcpy(d->rs, st->arena + d->head * st->W, (size_t)st->W);
        for (int f = 0; f < K; f++) s[f] = (uint32_t)cs_get(d->rs + st->off[f], st->w[f]);
        /* phase 1: everything this state needs is cached */
        int64_t narcs = 0, nadd = 0;
        status = -2;
        d->nreq = 0;
        d->ntmp = 0;
        for (int g = 0; g < d->G && status == -2; g++) {
            int nr = d->nread[g], nw = d->nwrite[g];
            uint32_t *key = d->req_key;
            for (int i = 0; i < nr; i++) key[i] = s[d->read[g][i]];
            int64_t o = -1;
            int tried = 0;
            d->in_tmp[g] = 0;
#ifdef ND_GENERATED
            if (d->uncached[g]) {
                d->scratch = 1;
                int rc = gen_group(d->gen, d, g, key);
                d->scratch = 0;
                tried = 1;
                if (rc == -2) { status = ND_NO_MEMORY; break; }
                if (rc == 0) { o = d->last_off; d->in_tmp[g] = 1; }
            }
#endif
            if (o < 0) {
                o = vm_get(&d->groups[g], key);
#ifdef ND_GENERATED
                if (d->gen) nd_judge(&d->looks[g], &d->misses[g], &d->uncached[g], d->uncache_after, o < 0);
                if (o < 0 && d->gen && !tried) {
                    int rc = gen_group(d->gen, d, g, key);
                    if (rc == -2) { status = ND_NO_MEMORY; break; }
                    if (rc == 0) o = d->last_off;
                }
#endif
            }
            if (o < 0) {
                if (grow((void **)&d->req, &d->req_cap, d->nreq + 2 + nr, 4) != 0) { status = ND_NO_MEMORY; break; }
                d->req[d->nreq++] = 0;
                d->req[d->nreq++] = (uint32_t)g;
                memcpy(d->req + d->nreq, key, (size_t)nr * 4);
                d->nreq += nr;
                break;
            }
            goff[g] = o;
            const int32_t *base = d->in_tmp[g] ? d->tmp : d->res;
            int64_t cnt = base[o];
            const int32_t *e = base + o + 1;
            for (int64_t j = 0; j < cnt; j++, e += 1 + nr + nw) {
                if (!d->be32 && e[0] > 65535) { status = ND_WIDE_BE; break; }
                if (nw && grow((void **)&d->addv, &d->addv_cap, nadd + nw, 4) != 0) { status = ND_NO_MEMORY; break; }
                for (int w = 0; w < nw; w++) {
                    uint32_t k[3] = {(uint32_t)d->write[g][w], (uint32_t)e[1 + nr + w], s[d->write[g][w]]};
                    int64_t v = -1;
#ifdef ND_GENERATED
                    int tried_add = 0;
                    if (d->adds_uncached) { v = gen_add(d->gen, k[0], k[1], k[2]); tried_add = 1; }
                    if (v < 0) {
                        v = vm_get(&d->adds, k);
                        if (d->gen) nd_judge(&d->adds_looks, &d->adds_misses, &d->adds_uncached, d->uncache_after, v < 0);
                    }
                    if (v < 0 && d->gen && !tried_add) {
                        int64_t nid = gen_add(d->gen, k[0], k[1], k[2]);
                        if (nid >= 0) {
                            if (vm_put(&d->adds, k, nid) != 0) { status = ND_NO_MEMORY; break; }
                            v = nid;
                        }
                    }
#else
                    v = vm_get(&d->adds, k);
#endif
                    if (v < 0) {
                        if (grow((void **)&d->req, &d->req_cap, d->nreq + 4, 4) != 0) { status = ND_NO_MEMORY; break; }
                        d->req[d->nreq++] = 1;
                        memcpy(d->req + d->nreq, k, sizeof k);
                        d->nreq += 3;
                        v = 0;
                    }
                    d->addv[nadd++] = (uint32_t)v;
                }
                if (status != -2) break;
            }
            narcs += cnt;
            /* what a group misses is asked for before any later group is looked at: the engine then
             * interns new markings in the order the Python search does (a marking's token order, and
             * so the order of the bindings found in it, is the order it was first built in) */
            if (d->nreq) break;
        }
        if (status == -2 && d->nreq) status = ND_NEED;
        if (status != -2) break;
        /* phase 2: the successors' records, in group order and each group's binding order; a value too
         * wide for its field widens the store's records and the records of this state are made anew */
        if (grow((void **)&d->dst, &d->arcs_cap, d->narcs + narcs, 4) != 0
            || grow(&d->bes, &d->bes_cap, d->narcs + narcs, 4) != 0
            || grow((void **)&d->offsets, &d->off_cap, d->noff + 1, 8) != 0
            || grow((void **)&d->parent, &d->new_cap, d->nnew + narcs, 4) != 0
            || grow((void **)&d->parent_be, &d->pbe_cap, d->nnew + narcs, 4) != 0
            || grow((void **)&d->hs, &d->hs_cap, narcs, 8) != 0) { status = ND_NO_MEMORY; break; }
        int failed = 0;
        for (;;) {
            int W = st->W, wf = -1;
            uint32_t wv = 0;
            if (grow((void **)&d->recs, &d->recs_cap, narcs * W, 1) != 0) { failed = 1; break; }
            const uint32_t *addv = d->addv;
            uint8_t *r = d->recs;
            for (int g = 0; g < d->G && wf < 0; g++) {
                int nr = d->nread[g], nw = d->nwrite[g];
                const int *rd = d->read[g], *wr = d->write[g];
                const int32_t *base = d->in_tmp[g] ? d->tmp : d->res;
                int64_t cnt = base[goff[g]];
                const int32_t *e = base + goff[g] + 1;
                for (int64_t j = 0; j < cnt && wf < 0; j++, e += 1 + nr + nw, r += W) {
                    memcpy(r, d->rs, (size_t)W);
                    for (int i = 0; i < nr; i++)
                        if (!cs_put(r + st->off[rd[i]], st->w[rd[i]], (uint32_t)e[1 + i])) {
                            wf = rd[i]; wv = (uint32_t)e[1 + i]; break;
                        }
                    for (int w = 0; w < nw && wf < 0; w++, addv++)
                        if (!cs_put(r + st->off[wr[w]], st->w[wr[w]], *addv)) { wf = wr[w]; wv = *addv; }
                }
            }
            if (wf < 0) break;
            if (cs_widen_field(st, wf, wv > 0xFFFFu ? 4 : 2) != 0) { failed = 1; break; }
            for (int f = 0; f < K; f++) cs_put(d->rs + st->off[f], st->w[f], s[f]);
        }
        if (failed) { status = ND_NO_MEMORY; break; }
        int W = st->W;
        for (int64_t k = 0; k < narcs; k++) {
            d->hs[k] = cs_hash(d->recs + k * W, W);
            __builtin_prefetch(cs_probe_start(st, d->hs[k]));
        }
        int64_t k = 0;
        for (int g = 0; g < d->G && !failed; g++) {
            int nr = d->nread[g], nw = d->nwrite[g];
            const int32_t *base = d->in_tmp[g] ? d->tmp : d->res;
            int64_t cnt = base[goff[g]];
            const int32_t *e = base + goff[g] + 1;
            for (int64_t j = 0; j < cnt; j++, e += 1 + nr + nw, k++) {
                int32_t id;
                int rc = cs_add_hashed(st, d->recs + k * W, d->hs[k], &id);
                if (rc < 0) { failed = 1; break; }
                if (rc == 1) {
                    d->parent[d->nnew] = (int32_t)d->head;
                    d->parent_be[d->nnew] = e[0];
                    d->nnew++;
                }
                d->dst[d->narcs] = id;
                if (d->be32) ((int32_t *)d->bes)[d->narcs] = e[0];
                else ((uint16_t *)d->bes)[d->narcs] = (uint16_t)e[0];
                d->narcs++;
            }
        }
        if (failed) { status = ND_NO_MEMORY; break; }
        d->total_arcs += narcs;
        d->offsets[d->noff++] = d->total_arcs;
        d->head++;
    }
    if (goff != off) free(goff);
    return status;
}

void nd_clear_batch(nd_search *d) { d->narcs = 0; d->noff = 0; d->nnew = 0; }
void nd_set_be32(nd_search *d) { d->be32 = 1; }
void nd_set_gen(nd_search *d, void *g) { d->gen = g; }
/* Judge each cache's hit rate after n lookups (n <= 0: never; every result is then cached). */
void nd_set_uncache_after(nd_search *d, int64_t n) {
    d->uncache_after = n > 0 ? n : -1;
    if (n <= 0) return;
    for (int g = 0; g < d->G; g++) { d->looks[g] = 0; d->misses[g] = 0; }
    d->adds_looks = 0; d->adds_misses = 0;
}
/* Go on from where another search over the same states stopped (its store copied into this one's). */
void nd_resume(nd_search *d, int64_t head, int64_t level_end, int64_t levels, int64_t total_arcs, int be32) {
    d->head = head; d->level_end = level_end; d->levels = levels; d->total_arcs = total_arcs; d->be32 = be32;
}
int64_t nd_head(nd_search *d) { return d->head; }
int64_t nd_levels(nd_search *d) { return d->levels; }
int64_t nd_level_end(nd_search *d) { return d->level_end; }
int64_t nd_total_arcs(nd_search *d) { return d->total_arcs; }
int64_t nd_narcs(nd_search *d) { return d->narcs; }
int64_t nd_noff(nd_search *d) { return d->noff; }
int64_t nd_nnew(nd_search *d) { return d->nnew; }
int32_t *nd_dst(nd_search *d) { return d->dst; }
void *nd_bes(nd_search *d) { return d->bes; }
int64_t *nd_offsets(nd_search *d) { return d->offsets; }
int32_t *nd_parent(nd_search *d) { return d->parent; }
int32_t *nd_parent_be(nd_search *d) { return d->parent_be; }
int64_t nd_nrequests(nd_search *d) { return d->nreq; }
uint32_t *nd_requests(nd_search *d) { return d->req; }
/* How many of the caches are judged rarely reused (the groups', then the written places' as one). */
int nd_uncached(nd_search *d) {
    int k = d->adds_uncached;
    for (int g = 0; g < d->G; g++) k += d->uncached[g];
    return k;
}
int64_t nd_cache_bytes(nd_search *d) {
    int64_t b = d->res_cap * 4 + d->tmp_cap * 4 + d->adds.cap * (12 + 8) + (int64_t)(d->adds.mask + 1) * 4;
    for (int g = 0; g < d->G; g++)
        b += d->groups[g].cap * (d->groups[g].len * 4 + 8) + (int64_t)(d->groups[g].mask + 1) * 4;
    return b;
}
