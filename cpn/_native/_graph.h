/* The standard report's graph algorithms (_graph.c): what Python calls (cpn/statespace/graphnative.py). */
#ifndef CPN_GRAPH_H
#define CPN_GRAPH_H

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* cffi: begin */
int64_t gr_scc(int64_t n, int64_t nexp, const int64_t *off, const int32_t *dst, int32_t *comp,
               int32_t *members, int32_t *start, uint8_t *terminal, uint8_t *nontrivial);
int gr_scc_arcs(int64_t nexp, const int64_t *off, const int32_t *dst, const int32_t *comp,
                const int32_t *members, const int32_t *start, int64_t count, int64_t *out);
int64_t gr_max_id(const void *ids, int bw, int64_t m);
void gr_mark_ids(const void *ids, int bw, int64_t m, uint8_t *seen);
void gr_map_ids(const void *ids, int bw, int64_t m, const int32_t *table, void *out, int ow);
int64_t gr_dead(int64_t nexp, const int64_t *off, int32_t *out);
int gr_reverse(int64_t n, int64_t nexp, const int64_t *off, const int32_t *dst, int64_t *poff, int32_t *pred);
int gr_live(int64_t n, int64_t nexp, const int64_t *off, const void *labels, int lw, int ntrans,
            const int32_t *comp, const int32_t *members, const int32_t *start, const uint8_t *terminal,
            int64_t count, uint8_t *live);
int gr_fairness(int64_t n, int64_t nexp, const int64_t *off, const int32_t *dst, const void *labels, int lw,
                int ntrans, const int32_t *comp, const int32_t *members, const int32_t *start,
                const uint8_t *nontrivial, int64_t count, uint8_t *cls);
int gr_columns(const uint8_t *arena, int64_t n, int size, int nf, const int32_t *fo, const int32_t *fw,
               const int64_t *so, const int64_t *cap, uint8_t *seen);
int64_t gr_max_sum(const uint8_t *arena, int64_t n, int size, int nf, const int32_t *fo, const int32_t *fw,
                   const int64_t *to, const int64_t *table);
int gr_eu(int64_t n, const int64_t *poff, const int32_t *pred, const uint8_t *phi, uint8_t *out);
void gr_ex(int64_t n, const int64_t *poff, const int32_t *pred, const uint8_t *target, uint8_t *out);
int gr_eg(int64_t n, int64_t nexp, const int64_t *off, const int32_t *dst, const int64_t *poff,
          const int32_t *pred, const uint8_t *dead, const uint8_t *phi, uint8_t *out);
void gr_label_rows(int64_t n, int64_t nexp, const int64_t *off, const void *labels, int lw, int ntrans,
                   uint8_t *out);
void gr_masks(int64_t n, int nprops, const uint8_t *props, int32_t *mask);
int gr_ltl(int64_t n, int64_t nexp, const int64_t *off, const int32_t *dst, const int32_t *mask,
           const int32_t *mtable, int32_t nm, int32_t nq, const int64_t *moff, const uint32_t *macc,
           const int32_t *mdst, int32_t q0, uint32_t full, int64_t *product_states);
void gr_add_i64(int64_t n, const int64_t *a, int64_t *acc);
void gr_le_i64(int64_t n, const int64_t *a, const int64_t *b, uint8_t *out);
void gr_le_const(int64_t n, const int64_t *a, int64_t c, int const_left, uint8_t *out);
/* cffi: end */

#endif
