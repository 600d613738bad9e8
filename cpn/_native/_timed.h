/* The native search of timed nets and nets with priorities (_timed.c, driving _search.c's search): what
 * Python calls. */
#ifndef CPN_TIMED_H
#define CPN_TIMED_H

#include "_search.h"

/* cffi: begin */
typedef struct nt_search nt_search;
nt_search *nt_new(nd_search *d, int clock, int condense, int prio, const int32_t *timed_g, int ntp,
                  const int32_t *tplaces);
void nt_free(nt_search *t);
void nt_set_watch(nt_search *t, int watch);
int64_t nt_level_start(nt_search *t);
int nt_put_ready(nt_search *t, int g, const uint32_t *key, int64_t n, const int64_t *pairs);
int nt_put_effect(nt_search *t, int g, const uint32_t *key, int64_t n, const int32_t *entries);
int nt_put_shift(nt_search *t, uint32_t p, uint32_t id, uint32_t f, uint32_t nid);
int nt_put_readies(nt_search *t, const int64_t *buf, int64_t n);
int nt_put_effects(nt_search *t, const int32_t *buf, int64_t n);
int nt_put_adds(nt_search *t, const uint32_t *buf, int64_t n);
int nt_put_shifts(nt_search *t, const uint32_t *buf, int64_t n);
int nt_run(nt_search *t, int64_t until, int64_t max_states, int64_t max_arcs);
int nt_put_views(nt_search *t, int p, int64_t from, int64_t n, const int32_t *ids);
int64_t nt_level_fresh(nt_search *t, int64_t start, int64_t end, int64_t *lo, int64_t *hi);
int64_t *nt_fresh(nt_search *t);
int64_t nt_cache_bytes(nt_search *t);
int nt_uncached(nt_search *t);
/* cffi: end */

#endif
