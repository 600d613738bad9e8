/* Graph algorithms of the standard report over the occurrence graph's arrays (cpn/statespace/graphnative.py).
 *
 * The graph is in CSR form: the arcs of state v are dst[off[v]:off[v+1]] for v < nexp (the expanded
 * states); states nexp..n-1 have no arcs. An arc's label (its transition instance) is read from an
 * array of 1, 2 or 4 bytes per arc (lw). Every function returns a negative number when memory runs out.
 *
 * gr_scc is Tarjan's algorithm, iterative, in exactly the order of the Python reference
 * (cpn/statespace/scc.py): roots in increasing order, arcs in CSR order, SCCs numbered as they complete,
 * members in the order they leave Tarjan's stack. So both give the same decomposition, number for number.
 */
#include "_graph.h"

#define ARCS_FROM(v) ((v) < nexp ? off[v] : 0)
#define ARCS_TO(v) ((v) < nexp ? off[(v) + 1] : 0)

static inline int32_t gr_label(const void *labels, int lw, int64_t i) {
    if (lw == 1) return ((const uint8_t *)labels)[i];
    if (lw == 2) return ((const uint16_t *)labels)[i];
    return ((const int32_t *)labels)[i];
}

/* ---------------------------------------------------------------- SCCs */

/* comp doubles as Tarjan's index: -1 unvisited, the DFS number (< n) while the state is on Tarjan's
 * stack, n + its SCC once that is complete (so one read per arc tells the three apart; the low links
 * live in the DFS frames). At the end comp holds the SCC numbers. n must be below 2^30. */
int64_t gr_scc(int64_t n, int64_t nexp, const int64_t *off, const int32_t *dst, int32_t *comp,
               int32_t *members, int32_t *start, uint8_t *terminal, uint8_t *nontrivial) {
    if (n >= ((int64_t)1 << 30)) return -2;
    int32_t *stack = (int32_t *)malloc((size_t)(n ? n : 1) * 4);
    int32_t *work = (int32_t *)malloc((size_t)(n ? n : 1) * 4);
    int32_t *lowf = (int32_t *)malloc((size_t)(n ? n : 1) * 4);
    int64_t *ptr = (int64_t *)malloc((size_t)(n ? n : 1) * 8);
    uint8_t *exits = (uint8_t *)calloc((size_t)(n ? n : 1), 1);
    int64_t ncomp = 0;
    const int32_t N = (int32_t)n;
    if (!stack || !work || !lowf || !ptr || !exits) { ncomp = -1; goto out; }
    for (int64_t v = 0; v < n; v++) comp[v] = -1;
    int32_t counter = 0;
    int64_t sp = 0, nmem = 0;
    start[0] = 0;
    for (int64_t root = 0; root < n; root++) {
        if (comp[root] != -1) continue;
        comp[root] = counter++;
        stack[sp++] = (int32_t)root;
        int64_t wp = 0;
        work[wp] = (int32_t)root;
        lowf[wp] = comp[root];
        ptr[wp] = ARCS_FROM(root);
        wp++;
        while (wp) {
            int32_t v = work[wp - 1];
            int64_t i = ptr[wp - 1], end = ARCS_TO(v);
            int32_t lv = lowf[wp - 1];
            int descended = 0;
            while (i < end) {
                int32_t w = dst[i++];
                int32_t cw = comp[w];
                if (cw == -1) {
                    lowf[wp - 1] = lv;
                    ptr[wp - 1] = i;
                    comp[w] = counter++;
                    stack[sp++] = w;
                    work[wp] = w;
                    lowf[wp] = comp[w];
                    ptr[wp] = ARCS_FROM(w);
                    wp++;
                    descended = 1;
                    break;
                }
                if (cw < N) {
                    if (cw < lv) lv = cw;
                } else {
                    exits[v] = 1;
                }
            }
            if (descended) continue;
            wp--;
            if (lv == comp[v]) {
                int64_t first = nmem;
                uint8_t term = 1;
                for (;;) {
                    int32_t w = stack[--sp];
                    comp[w] = N + (int32_t)ncomp;
                    members[nmem++] = w;
                    if (exits[w]) term = 0;
                    if (w == v) break;
                }
                uint8_t nt = nmem - first > 1;
                for (int64_t j = ARCS_FROM(v); !nt && j < ARCS_TO(v); j++)
                    if (dst[j] == v) nt = 1;
                start[ncomp + 1] = (int32_t)nmem;
                terminal[ncomp] = term;
                nontrivial[ncomp] = nt;
                ncomp++;
                if (wp) exits[work[wp - 1]] = 1;
            } else if (wp) {
                if (lv < lowf[wp - 1]) lowf[wp - 1] = lv;
            }
        }
    }
    for (int64_t v = 0; v < n; v++) comp[v] -= N;
out:
    free(stack); free(work); free(lowf); free(ptr); free(exits);
    return ncomp;
}

/* Arcs of the SCC graph: out[0] arcs whose ends lie in different SCCs, out[1] distinct ordered pairs. */
int gr_scc_arcs(int64_t nexp, const int64_t *off, const int32_t *dst, const int32_t *comp,
                const int32_t *members, const int32_t *start, int64_t count, int64_t *out) {
    int32_t *mark = (int32_t *)malloc((size_t)(count ? count : 1) * 4);
    if (!mark) return -1;
    for (int64_t c = 0; c < count; c++) mark[c] = -1;
    int64_t total = 0, pairs = 0;
    for (int64_t c = 0; c < count; c++) {
        for (int64_t k = start[c]; k < start[c + 1]; k++) {
            int32_t v = members[k];
            for (int64_t j = ARCS_FROM(v); j < ARCS_TO(v); j++) {
                int32_t cw = comp[dst[j]];
                if (cw != c) {
                    total++;
                    if (mark[cw] != c) { mark[cw] = (int32_t)c; pairs++; }
                }
            }
        }
    }
    free(mark);
    out[0] = total;
    out[1] = pairs;
    return 0;
}

/* ---------------------------------------------------------------- arcs, dead states, live transitions */

/* The largest value of an array of m unsigned ids of bw bytes (-1 if m == 0). */
int64_t gr_max_id(const void *ids, int bw, int64_t m) {
    int64_t best = -1;
    for (int64_t i = 0; i < m; i++) {
        int64_t v = gr_label(ids, bw, i);
        if (v > best) best = v;
    }
    return best;
}

/* seen[id] = 1 for every id of the array. */
void gr_mark_ids(const void *ids, int bw, int64_t m, uint8_t *seen) {
    for (int64_t i = 0; i < m; i++) seen[gr_label(ids, bw, i)] = 1;
}

/* out[i] = table[ids[i]], out of ow bytes per entry. */
void gr_map_ids(const void *ids, int bw, int64_t m, const int32_t *table, void *out, int ow) {
    for (int64_t i = 0; i < m; i++) {
        int32_t t = table[gr_label(ids, bw, i)];
        if (ow == 1) ((uint8_t *)out)[i] = (uint8_t)t;
        else if (ow == 2) ((uint16_t *)out)[i] = (uint16_t)t;
        else ((int32_t *)out)[i] = t;
    }
}

/* The expanded states without arcs, increasing, into out; returns how many. */
int64_t gr_dead(int64_t nexp, const int64_t *off, int32_t *out) {
    int64_t k = 0;
    for (int64_t v = 0; v < nexp; v++)
        if (off[v] == off[v + 1]) out[k++] = (int32_t)v;
    return k;
}

/* Predecessors in CSR form: the sources of the arcs into v, in the order of the arcs, are
 * pred[poff[v]..poff[v + 1]) (a counting sort of the arcs by target). 0, or -1 without memory. */
int gr_reverse(int64_t n, int64_t nexp, const int64_t *off, const int32_t *dst, int64_t *poff, int32_t *pred) {
    int64_t m = off[nexp];
    int64_t *next = (int64_t *)malloc((size_t)(n ? n : 1) * 8);
    if (!next) return -1;
    memset(poff, 0, (size_t)(n + 1) * 8);
    for (int64_t i = 0; i < m; i++) poff[dst[i] + 1]++;
    for (int64_t v = 0; v < n; v++) poff[v + 1] += poff[v];
    memcpy(next, poff, (size_t)n * 8);
    for (int64_t u = 0; u < nexp; u++)
        for (int64_t i = off[u]; i < off[u + 1]; i++) pred[next[dst[i]]++] = (int32_t)u;
    free(next);
    return 0;
}

/* live[t] = 1 iff t labels an arc leaving a state of every terminal SCC (arcs of a terminal SCC stay in
 * it). The terminal SCCs of at least n / 8 states (at most 8) are read in one pass over the states in
 * increasing order (the order the arcs are stored in); the others state by state. */
int gr_live(int64_t n, int64_t nexp, const int64_t *off, const void *labels, int lw, int ntrans,
            const int32_t *comp, const int32_t *members, const int32_t *start, const uint8_t *terminal,
            int64_t count, uint8_t *live) {
    enum { BIG = 8 };
    int nt_ = ntrans ? ntrans : 1;
    int64_t *stamp = (int64_t *)malloc((size_t)nt_ * 8);
    int32_t *bigidx = (int32_t *)calloc((size_t)(count ? count : 1), 4);
    uint8_t *seen = (uint8_t *)calloc((size_t)nt_ * BIG, 1);
    if (!stamp || !bigidx || !seen) { free(stamp); free(bigidx); free(seen); return -1; }
    int nbig = 0;
    for (int64_t c = 0; c < count; c++)
        if (terminal[c] && (int64_t)(start[c + 1] - start[c]) * BIG >= n && nbig < BIG) bigidx[c] = ++nbig;
    if (nbig) {
        for (int64_t v = 0; v < nexp; v++) {
            int b = bigidx[comp[v]] - 1;
            if (b < 0) continue;
            for (int64_t j = off[v]; j < off[v + 1]; j++) seen[gr_label(labels, lw, j) * BIG + b] = 1;
        }
    }
    for (int t = 0; t < ntrans; t++) { live[t] = 1; stamp[t] = -1; }
    for (int64_t c = 0; c < count; c++) {
        if (!terminal[c]) continue;
        if (bigidx[c]) {
            int b = bigidx[c] - 1;
            for (int t = 0; t < ntrans; t++)
                if (!seen[t * BIG + b]) live[t] = 0;
            continue;
        }
        for (int64_t k = start[c]; k < start[c + 1]; k++) {
            int32_t v = members[k];
            for (int64_t j = ARCS_FROM(v); j < ARCS_TO(v); j++) stamp[gr_label(labels, lw, j)] = c;
        }
        for (int t = 0; t < ntrans; t++)
            if (stamp[t] != c) live[t] = 0;
    }
    free(stamp); free(bigidx); free(seen);
    return 0;
}

/* ---------------------------------------------------------------- fairness */

/* The searches of one transition instance t: over arcs not labelled t whose two ends lie in the same
 * SCC of the graph (a cycle lies in one), from the roots that pass is_root. Whether a state enables t
 * is found when first needed (reading its arcs) and remembered in emark. */
typedef struct {
    int64_t nexp;
    const int64_t *off;
    const int32_t *dst;
    const void *labels;
    int lw;
    const int32_t *comp;
    int32_t t;
    int32_t *emark;          /* per state: 2t+2 if it enables t, 2t+3 if not, anything else: not known */
    const int32_t *cstamp;   /* roots only in the SCCs c with cstamp[c] == ckey (NULL: no such test) */
    int32_t ckey;
    const int32_t *roots;
    int64_t nroots;
    uint8_t *colour, *done;  /* n bytes each: colour zeroed before each cycle search, done kept zero */
    int32_t *index, *low;    /* n entries each: index kept at -1 between searches */
    int32_t *stack, *work, *touched;
    int64_t *ptr;
} fsearch;

static inline int enables(fsearch *f, int32_t v) {
    int32_t m = f->emark[v], yes = 2 * f->t + 2;
    if (m == yes) return 1;
    if (m == yes + 1) return 0;
    int64_t nexp = f->nexp;
    const int64_t *off = f->off;
    for (int64_t j = ARCS_FROM(v); j < ARCS_TO(v); j++)
        if (gr_label(f->labels, f->lw, j) == f->t) { f->emark[v] = yes; return 1; }
    f->emark[v] = yes + 1;
    return 0;
}

static inline int is_root(fsearch *f, int32_t v, int only_enabled) {
    if (f->cstamp != NULL && f->cstamp[f->comp[v]] != f->ckey) return 0;
    return !only_enabled || enables(f, v);
}

/* Whether a cycle avoiding t is reachable from the roots (through states enabling t with only_enabled).
 * Stops at the first arc back to the DFS stack. */
static int cycle_avoiding(fsearch *f, int only_enabled) {
    int64_t nexp = f->nexp;
    const int64_t *off = f->off;
    const int32_t *dst = f->dst, *comp = f->comp;
    uint8_t *colour = f->colour;
    int32_t *work = f->work, t = f->t;
    int64_t *ptr = f->ptr;
    for (int64_t r = 0; r < f->nroots; r++) {
        int32_t root = f->roots[r];
        if (colour[root] || !is_root(f, root, only_enabled)) continue;
        colour[root] = 1;
        int64_t wp = 0;
        work[wp] = root;
        ptr[wp] = ARCS_FROM(root);
        wp++;
        while (wp) {
            int32_t v = work[wp - 1];
            int64_t i = ptr[wp - 1], end = ARCS_TO(v);
            int32_t cv = comp[v];
            int descended = 0;
            while (i < end) {
                int64_t a = i++;
                if (gr_label(f->labels, f->lw, a) == t) continue;
                int32_t w = dst[a];
                if (comp[w] != cv) continue;
                if (colour[w] == 1) return 1;
                if (colour[w] == 0 && (!only_enabled || enables(f, w))) {
                    ptr[wp - 1] = i;
                    colour[w] = 1;
                    work[wp] = w;
                    ptr[wp] = ARCS_FROM(w);
                    wp++;
                    descended = 1;
                    break;
                }
            }
            if (!descended) { colour[v] = 2; wp--; }
        }
    }
    return 0;
}

/* Whether the graph less the arcs labelled t has a nontrivial SCC (a self-loop counts) through a state
 * enabling t, among those reachable from the roots enabling t (Tarjan, stopping at the first). */
static int component_through(fsearch *f) {
    int64_t nexp = f->nexp;
    const int64_t *off = f->off;
    const int32_t *dst = f->dst, *comp = f->comp;
    int32_t *index = f->index, *low = f->low, *stack = f->stack, *work = f->work, *touched = f->touched;
    int64_t *ptr = f->ptr;
    uint8_t *done = f->done;
    int32_t t = f->t, counter = 0;
    int64_t nt = 0, sp = 0;
    int found = 0;
    for (int64_t r = 0; r < f->nroots && !found; r++) {
        int32_t root = f->roots[r];
        if (index[root] != -1 || !is_root(f, root, 1)) continue;
        index[root] = low[root] = counter++;
        touched[nt++] = root;
        stack[sp++] = root;
        int64_t wp = 0;
        work[wp] = root;
        ptr[wp] = ARCS_FROM(root);
        wp++;
        while (wp && !found) {
            int32_t v = work[wp - 1];
            int64_t i = ptr[wp - 1], end = ARCS_TO(v);
            int32_t lv = low[v], cv = comp[v];
            int descended = 0;
            while (i < end) {
                int64_t a = i++;
                if (gr_label(f->labels, f->lw, a) == t) continue;
                int32_t w = dst[a];
                if (comp[w] != cv) continue;
                int32_t iw = index[w];
                if (iw == -1) {
                    low[v] = lv;
                    ptr[wp - 1] = i;
                    index[w] = low[w] = counter++;
                    touched[nt++] = w;
                    stack[sp++] = w;
                    work[wp] = w;
                    ptr[wp] = ARCS_FROM(w);
                    wp++;
                    descended = 1;
                    break;
                }
                if (!done[w] && iw < lv) lv = iw;
            }
            if (descended) continue;
            low[v] = lv;
            wp--;
            if (lv == index[v]) {
                int64_t size = 0;
                int hit = 0;
                for (;;) {
                    int32_t w = stack[--sp];
                    done[w] = 1;
                    size++;
                    if (!hit && enables(f, w)) hit = 1;
                    if (w == v) break;
                }
                if (hit) {
                    if (size > 1) found = 1;
                    for (int64_t j = ARCS_FROM(v); !found && j < ARCS_TO(v); j++)
                        if (dst[j] == v && gr_label(f->labels, f->lw, j) != t) found = 1;
                }
            } else if (wp) {
                int32_t u = work[wp - 1];
                if (lv < low[u]) low[u] = lv;
            }
        }
    }
    for (int64_t k = 0; k < nt; k++) { index[touched[k]] = -1; done[touched[k]] = 0; }
    return found;
}

/* Fairness class of every transition instance (0 impartial, 1 fair, 2 just, 3 none) into cls, given the
 * SCC decomposition; the graph must have a nontrivial SCC. One pass over the states of the nontrivial
 * SCCs finds, per transition instance t, the nontrivial SCCs where t is enabled and those where t labels
 * an arc inside. Then per t:
 * - t never enabled in a nontrivial SCC: fair;
 * - t labels an arc inside every nontrivial SCC: impartial unless a cycle avoids t (a search over the
 *   nontrivial SCCs, stopping at the first cycle);
 * - a cycle avoiding t through states enabling t: none;
 * - some nontrivial SCC enables t and has no arc of t inside (it is strongly connected without t), or
 *   the graph less t has a nontrivial SCC through a state enabling t: just; else fair.
 * The last two searches start only from the states enabling t in the SCCs where t is enabled. */
int gr_fairness(int64_t n, int64_t nexp, const int64_t *off, const int32_t *dst, const void *labels, int lw,
                int ntrans, const int32_t *comp, const int32_t *members, const int32_t *start,
                const uint8_t *nontrivial, int64_t count, uint8_t *cls) {
    int nt_ = ntrans ? ntrans : 1;
    int64_t n1 = n ? n : 1, c1 = count ? count : 1;
    int64_t *en_count = (int64_t *)calloc((size_t)nt_, 8), *in_count = (int64_t *)calloc((size_t)nt_, 8);
    int64_t *stamp_e = (int64_t *)malloc((size_t)nt_ * 8), *stamp_i = (int64_t *)malloc((size_t)nt_ * 8);
    int64_t *coff = (int64_t *)calloc((size_t)nt_ + 1, 8), *cfill = (int64_t *)malloc((size_t)nt_ * 8);
    uint8_t *not_fair = (uint8_t *)calloc((size_t)nt_, 1);
    int32_t *touched_t = (int32_t *)malloc((size_t)nt_ * 4), *cstamp = (int32_t *)calloc((size_t)c1, 4);
    int32_t *pair_t = NULL, *pair_c = NULL, *comps = NULL;
    int64_t npairs = 0, pairs_cap = 1024;
    fsearch f;
    memset(&f, 0, sizeof f);
    f.emark = (int32_t *)calloc((size_t)n1, 4);
    f.index = (int32_t *)malloc((size_t)n1 * 4);
    f.low = (int32_t *)malloc((size_t)n1 * 4);
    f.stack = (int32_t *)malloc((size_t)n1 * 4);
    f.work = (int32_t *)malloc((size_t)n1 * 4);
    f.touched = (int32_t *)malloc((size_t)n1 * 4);
    f.ptr = (int64_t *)malloc((size_t)n1 * 8);
    f.colour = (uint8_t *)malloc((size_t)n1);
    f.done = (uint8_t *)calloc((size_t)n1, 1);
    int32_t *all = (int32_t *)malloc((size_t)n1 * 4), *some = (int32_t *)malloc((size_t)n1 * 4);
    pair_t = (int32_t *)malloc((size_t)pairs_cap * 4);
    pair_c = (int32_t *)malloc((size_t)pairs_cap * 4);
    int rc = 0;
    if (!en_count || !in_count || !stamp_e || !stamp_i || !coff || !cfill || !not_fair || !touched_t || !cstamp
        || !f.emark || !f.index || !f.low || !f.stack || !f.work || !f.touched || !f.ptr || !f.colour || !f.done
        || !all || !some || !pair_t || !pair_c) { rc = -1; goto out; }
    f.nexp = nexp; f.off = off; f.dst = dst; f.labels = labels; f.lw = lw; f.comp = comp;
    for (int64_t v = 0; v < n; v++) f.index[v] = -1;
    /* one pass over the states of the nontrivial SCCs: the (t, SCC) pairs where t is enabled, and how
     * many SCCs have an arc of t inside */
    /* The SCCs of at least n / BIG states (at most BIG of them) are read in one pass over the states in
     * increasing order, which reads the arcs in the order they are stored; the others SCC by SCC. */
    enum { BIG = 8 };
    int64_t ncyc = 0;
    int nbig = 0;
    uint8_t *big_en = (uint8_t *)calloc((size_t)nt_ * BIG, 1), *big_in = (uint8_t *)calloc((size_t)nt_ * BIG, 1);
    if (!big_en || !big_in) { free(big_en); free(big_in); rc = -1; goto out; }
    for (int64_t c = 0; c < count; c++) {
        if (!nontrivial[c]) continue;
        ncyc++;
        if ((int64_t)(start[c + 1] - start[c]) * BIG >= n && nbig < BIG) { cstamp[c] = ++nbig; }
    }
    if (nbig) {
        for (int64_t v = 0; v < nexp; v++) {
            int32_t c = comp[v];
            int b = cstamp[c] - 1;
            if (b < 0) continue;
            for (int64_t j = off[v]; j < off[v + 1]; j++) {
                int32_t t = gr_label(labels, lw, j);
                big_en[t * BIG + b] = 1;
                if (comp[dst[j]] == c) big_in[t * BIG + b] = 1;
            }
        }
    }
    for (int t = 0; t < ntrans; t++) stamp_e[t] = stamp_i[t] = -1;
    for (int64_t c = 0; c < count; c++) {
        if (!nontrivial[c]) continue;
        int ntt = 0;
        if (cstamp[c]) {
            int b = cstamp[c] - 1;
            for (int t = 0; t < ntrans; t++) {
                if (big_en[t * BIG + b]) { stamp_e[t] = c; en_count[t]++; touched_t[ntt++] = t; }
                if (big_in[t * BIG + b]) { stamp_i[t] = c; in_count[t]++; }
            }
        } else {
            for (int64_t k = start[c]; k < start[c + 1]; k++) {
                int32_t v = members[k];
                for (int64_t j = ARCS_FROM(v); j < ARCS_TO(v); j++) {
                    int32_t t = gr_label(labels, lw, j);
                    if (stamp_e[t] != c) { stamp_e[t] = c; en_count[t]++; touched_t[ntt++] = t; }
                    if (stamp_i[t] != c && comp[dst[j]] == c) { stamp_i[t] = c; in_count[t]++; }
                }
            }
        }
        for (int k = 0; k < ntt; k++) {
            int32_t t = touched_t[k];
            if (stamp_i[t] != c) not_fair[t] = 1;
            if (npairs == pairs_cap) {
                pairs_cap *= 2;
                int32_t *pt = (int32_t *)realloc(pair_t, (size_t)pairs_cap * 4);
                if (pt) pair_t = pt;
                int32_t *pc = (int32_t *)realloc(pair_c, (size_t)pairs_cap * 4);
                if (pc) pair_c = pc;
                if (!pt || !pc) { rc = -1; goto out; }
            }
            pair_t[npairs] = t;
            pair_c[npairs++] = (int32_t)c;
        }
    }
    free(big_en);
    free(big_in);
    memset(cstamp, 0, (size_t)c1 * 4);
    /* the nontrivial SCCs enabling each t (CSR by t), and every state of a nontrivial SCC, increasing */
    for (int t = 0; t < ntrans; t++) coff[t + 1] = coff[t] + en_count[t];
    comps = (int32_t *)malloc((size_t)(npairs ? npairs : 1) * 4);
    if (!comps) { rc = -1; goto out; }
    for (int t = 0; t < ntrans; t++) cfill[t] = coff[t];
    for (int64_t q = 0; q < npairs; q++) comps[cfill[pair_t[q]]++] = pair_c[q];
    int64_t nall = 0;
    for (int64_t v = 0; v < n; v++)
        if (nontrivial[comp[v]]) all[nall++] = (int32_t)v;
    for (int t = 0; t < ntrans; t++) {
        f.t = t;
        if (en_count[t] == 0) { cls[t] = 1; continue; }
        if (in_count[t] == ncyc) {
            f.cstamp = NULL; f.roots = all; f.nroots = nall;
            memset(f.colour, 0, (size_t)n1);
            if (!cycle_avoiding(&f, 0)) { cls[t] = 0; continue; }
        }
        /* roots: the states of the SCCs enabling t (read in increasing order when they are many) */
        int64_t size = 0;
        for (int64_t q = coff[t]; q < coff[t + 1]; q++) size += start[comps[q] + 1] - start[comps[q]];
        if (4 * size >= nall) {
            for (int64_t q = coff[t]; q < coff[t + 1]; q++) cstamp[comps[q]] = t + 1;
            f.cstamp = cstamp; f.ckey = t + 1; f.roots = all; f.nroots = nall;
        } else {
            int64_t k = 0;
            for (int64_t q = coff[t]; q < coff[t + 1]; q++)
                for (int64_t m = start[comps[q]]; m < start[comps[q] + 1]; m++) some[k++] = members[m];
            f.cstamp = NULL; f.roots = some; f.nroots = k;
        }
        memset(f.colour, 0, (size_t)n1);
        if (cycle_avoiding(&f, 1))
            cls[t] = 3;
        else if (not_fair[t] || component_through(&f))
            cls[t] = 2;
        else
            cls[t] = 1;
    }
out:
    free(en_count); free(in_count); free(stamp_e); free(stamp_i); free(coff); free(cfill); free(not_fair);
    free(touched_t); free(cstamp); free(pair_t); free(pair_c); free(comps); free(all); free(some);
    free(f.emark); free(f.index); free(f.low); free(f.stack); free(f.work); free(f.touched); free(f.ptr);
    free(f.colour); free(f.done);
    return rc;
}

/* ---------------------------------------------------------------- place columns of packed states */

static inline uint64_t field_at(const uint8_t *rec, int o, int w) {
    uint64_t v = 0;
    for (int b = w - 1; b >= 0; b--) v = (v << 8) | rec[o + b];
    return v;
}

/* For each of nf fields (byte offset fo[f], width fw[f] of records of size bytes): seen[so[f] + value] = 1.
 * Returns 0, or f + 1 when a value of field f is at least cap[f] (nothing is then promised). */
int gr_columns(const uint8_t *arena, int64_t n, int size, int nf, const int32_t *fo, const int32_t *fw,
               const int64_t *so, const int64_t *cap, uint8_t *seen) {
    for (int64_t i = 0; i < n; i++) {
        const uint8_t *rec = arena + i * size;
        for (int f = 0; f < nf; f++) {
            uint64_t v = field_at(rec, fo[f], fw[f]);
            if (v >= (uint64_t)cap[f]) return f + 1;
            seen[so[f] + v] = 1;
        }
    }
    return 0;
}

/* The largest sum over the nf fields of table[to[f] + value] over all records (values checked by gr_columns). */
int64_t gr_max_sum(const uint8_t *arena, int64_t n, int size, int nf, const int32_t *fo, const int32_t *fw,
                   const int64_t *to, const int64_t *table) {
    int64_t best = 0;
    for (int64_t i = 0; i < n; i++) {
        const uint8_t *rec = arena + i * size;
        int64_t s = 0;
        for (int f = 0; f < nf; f++) s += table[to[f] + field_at(rec, fo[f], fw[f])];
        if (s > best) best = s;
    }
    return best;
}

/* ---------------------------------------------------------------- CTL fixpoints
 * Over the predecessors in CSR form (gr_reverse) and 0/1 bytes per state; the results are those of the
 * Python labelling (cpn/checks/ctl.py's Kripke), which tests compare on random graphs. */

/* E[phi U psi]: out holds the psi-states on entry; every phi-state with a path through phi-states to one
 * of them is added (a breadth-first search backwards). 0, or -1 without memory. */
int gr_eu(int64_t n, const int64_t *poff, const int32_t *pred, const uint8_t *phi, uint8_t *out) {
    int32_t *queue = (int32_t *)malloc((size_t)(n ? n : 1) * 4);
    if (!queue) return -1;
    int64_t head = 0, tail = 0;
    for (int64_t v = 0; v < n; v++)
        if (out[v]) queue[tail++] = (int32_t)v;
    while (head < tail) {
        int32_t v = queue[head++];
        for (int64_t i = poff[v]; i < poff[v + 1]; i++) {
            int32_t u = pred[i];
            if (!out[u] && phi[u]) {
                out[u] = 1;
                queue[tail++] = u;
            }
        }
    }
    free(queue);
    return 0;
}

/* EX target: out[u] = 1 for every state u with an arc into a target state (out zeroed by the caller). */
void gr_ex(int64_t n, const int64_t *poff, const int32_t *pred, const uint8_t *target, uint8_t *out) {
    for (int64_t v = 0; v < n; v++)
        if (target[v])
            for (int64_t i = poff[v]; i < poff[v + 1]; i++) out[pred[i]] = 1;
}

/* EG phi without fairness: the largest set of phi-states each of which is dead or has an arc into the
 * set (a path staying in phi forever or to a dead phi-state), computed by counting each state's arcs
 * into the set and removing the states whose count falls to zero. The same states as the dead
 * phi-states and the nontrivial SCCs of the phi-sub-graph closed backwards within phi. out gets the
 * set; 0, or -1 without memory. */
int gr_eg(int64_t n, int64_t nexp, const int64_t *off, const int32_t *dst, const int64_t *poff,
          const int32_t *pred, const uint8_t *dead, const uint8_t *phi, uint8_t *out) {
    int64_t *count = (int64_t *)calloc((size_t)(n ? n : 1), 8);
    int32_t *queue = (int32_t *)malloc((size_t)(n ? n : 1) * 4);
    if (!count || !queue) {
        free(count);
        free(queue);
        return -1;
    }
    int64_t head = 0, tail = 0;
    for (int64_t v = 0; v < n; v++) {
        out[v] = phi[v] ? 1 : 0;
        if (!phi[v] || dead[v]) continue;
        int64_t k = 0;
        for (int64_t i = ARCS_FROM(v); i < ARCS_TO(v); i++) k += phi[dst[i]] ? 1 : 0;
        count[v] = k;
        if (k == 0) {
            out[v] = 0;
            queue[tail++] = (int32_t)v;
        }
    }
    while (head < tail) {
        int32_t v = queue[head++];
        for (int64_t i = poff[v]; i < poff[v + 1]; i++) {
            int32_t u = pred[i];
            if (out[u] && !dead[u] && --count[u] == 0) {
                out[u] = 0;
                queue[tail++] = u;
            }
        }
    }
    free(count);
    free(queue);
    return 0;
}

/* Per label t < ntrans, the states with an arc labelled t: out[t * n + u] = 1 (out zeroed by the caller;
 * every label below ntrans). */
void gr_label_rows(int64_t n, int64_t nexp, const int64_t *off, const void *labels, int lw, int ntrans,
                   uint8_t *out) {
    for (int64_t u = 0; u < nexp; u++)
        for (int64_t i = off[u]; i < off[u + 1]; i++) {
            int32_t t = gr_label(labels, lw, i);
            if (t >= 0 && t < ntrans) out[(int64_t)t * n + u] = 1;
        }
}

/* ---------------------------------------------------------------- LTL over a complete graph
 * The product of the graph with a generalised Büchi automaton (labels and acceptance sets on the edges,
 * cpn/checks/buchi.py's Automaton) searched for an accepting cycle by Couvreur's SCC-based algorithm,
 * as cpn/checks/ltl.py does on the fly: a depth-first search keeping a stack of SCC roots with the
 * acceptance sets met inside each, stopping when one root has met them all. Product state s * nq + q.
 * The automaton reads the present state's propositions: state s has the proposition mask mask[s],
 * numbered mtable[mask[s]] among the nm distinct masks, and from automaton state q a state with mask
 * number k moves along the edges moff[q * nm + k] .. moff[q * nm + k + 1] (to mdst, meeting the sets
 * macc). A state without arcs (dead) repeats forever (a stutter step to itself), as the contest reads a
 * deadlock. Returns 1 when there is an accepting cycle, 0 when there is none, -1 without memory, -2 when
 * the product has 2^31 states or more. */

/* mask[s] = the bits b < nprops with props[b * n + s] set. */
void gr_masks(int64_t n, int nprops, const uint8_t *props, int32_t *mask) {
    memset(mask, 0, (size_t)n * 4);
    for (int b = 0; b < nprops; b++)
        for (int64_t s = 0; s < n; s++)
            if (props[(int64_t)b * n + s]) mask[s] |= (int32_t)1 << b;
}

/* a depth-first frame: the product state, its next system arc and next automaton move (the ranges are
 * recomputed from v: deep searches keep millions of frames) */
typedef struct {
    int64_t v, i;
    int32_t j;
} ltl_frame;

#define GROW(ptr, cap, len, type)                                                  \
    do {                                                                           \
        if ((len) == (cap)) {                                                      \
            int64_t ncap_ = (cap) ? 2 * (cap) : 1024;                              \
            type *np_ = (type *)realloc((ptr), (size_t)ncap_ * sizeof(type));      \
            if (!np_) goto nomem;                                                  \
            (ptr) = np_;                                                           \
            (cap) = ncap_;                                                         \
        }                                                                          \
    } while (0)

int gr_ltl(int64_t n, int64_t nexp, const int64_t *off, const int32_t *dst, const int32_t *mask,
           const int32_t *mtable, int32_t nm, int32_t nq, const int64_t *moff, const uint32_t *macc,
           const int32_t *mdst, int32_t q0, uint32_t full, int64_t *product_states) {
    if (n <= 0 || nq <= 0) return 0;
    if ((int64_t)n * nq >= ((int64_t)1 << 31) - 2) return -2;
    int result = -1;
    int32_t *index = (int32_t *)calloc((size_t)(n * nq), 4); /* 0 unvisited, -1 done, else DFS number */
    ltl_frame *todo = NULL;
    int64_t *live = NULL;
    int32_t *rnum = NULL;
    uint32_t *rin = NULL, *redge = NULL;
    int64_t ntodo = 0, ctodo = 0, nlive = 0, clive = 0, nroots = 0, croots = 0, crin = 0, credge = 0;
    int32_t counter = 0;
    if (!index) goto nomem;

    int64_t w = q0; /* the initial product state: state 0, the automaton's initial state */
    uint32_t wacc = 0;
    for (;;) {
        /* push w, reached by an edge meeting the sets wacc */
        index[w] = ++counter;
        GROW(rnum, croots, nroots, int32_t);
        GROW(rin, crin, nroots, uint32_t);
        GROW(redge, credge, nroots, uint32_t);
        rnum[nroots] = counter;
        rin[nroots] = 0;
        redge[nroots] = wacc;
        nroots++;
        GROW(live, clive, nlive, int64_t);
        live[nlive++] = w;
        GROW(todo, ctodo, ntodo, ltl_frame);
        {
            int64_t s = w / nq;
            ltl_frame *f = &todo[ntodo++];
            f->v = w;
            f->i = ARCS_FROM(s);
            f->j = (int32_t)moff[(w % nq) * nm + mtable[mask[s]]];
        }
        /* descend or backtrack until a new product state is found */
        int found_new = 0;
        while (ntodo && !found_new) {
            ltl_frame *f = &todo[ntodo - 1];
            int64_t s = f->v / nq, row = (f->v % nq) * nm + mtable[mask[s]];
            int64_t jstart = moff[row], jend = moff[row + 1];
            int64_t ifrom = ARCS_FROM(s), iend = ARCS_TO(s);
            int stutter = ifrom == iend;
            if (stutter) iend = ifrom + 1;
            if (f->j == jend) {
                f->i++;
                f->j = (int32_t)jstart;
            }
            if (f->i >= iend || jstart == jend) {
                /* every successor seen: close the SCC if v is its root */
                int64_t v = f->v;
                ntodo--;
                if (rnum[nroots - 1] == index[v]) {
                    nroots--;
                    for (;;) {
                        int64_t x = live[--nlive];
                        index[x] = -1;
                        if (x == v) break;
                    }
                }
                continue;
            }
            int64_t t = stutter ? s : dst[f->i];
            int64_t e = f->j++;
            w = t * nq + mdst[e];
            wacc = macc[e];
            int32_t iw = index[w];
            if (iw == 0) {
                found_new = 1;
                break;
            }
            if (iw < 0) continue;
            uint32_t met = wacc;
            while (rnum[nroots - 1] > iw) {
                nroots--;
                met |= rin[nroots] | redge[nroots];
            }
            rin[nroots - 1] |= met;
            if (rin[nroots - 1] == full) {
                result = 1;
                goto out;
            }
        }
        if (!found_new) {
            result = 0;
            goto out;
        }
    }
nomem:
    result = -1;
out:
    if (product_states) *product_states = counter;
    free(index);
    free(todo);
    free(live);
    free(rnum);
    free(rin);
    free(redge);
    return result;
}

/* ---------------------------------------------------------------- integer columns (contest formulas) */

/* acc[i] += a[i] */
void gr_add_i64(int64_t n, const int64_t *a, int64_t *acc) {
    for (int64_t i = 0; i < n; i++) acc[i] += a[i];
}

/* out[i] = a[i] <= b[i] */
void gr_le_i64(int64_t n, const int64_t *a, const int64_t *b, uint8_t *out) {
    for (int64_t i = 0; i < n; i++) out[i] = a[i] <= b[i];
}

/* out[i] = a[i] <= c (const_left 0), or c <= a[i] (const_left 1) */
void gr_le_const(int64_t n, const int64_t *a, int64_t c, int const_left, uint8_t *out) {
    if (const_left)
        for (int64_t i = 0; i < n; i++) out[i] = c <= a[i];
    else
        for (int64_t i = 0; i < n; i++) out[i] = a[i] <= c;
}
