/* The multi-threaded native search (_threads.c, over _search.c's caches and the net's C of _cnet.c): what
 * Python calls. Built with ND_THREADS and ND_GENERATED defined (cpn/_native/manifest.py). */
#ifndef CPN_THREADS_H
#define CPN_THREADS_H

#include "_search.h"

/* cffi: begin */
typedef struct th_search th_search;
th_search *th_new(int n, int K, int G, const int32_t *nread, const int32_t *nwrite, const int32_t *fields,
                  void *gen, const uint32_t *s0, const uint8_t *widths, int64_t max_states, int64_t max_arcs,
                  int64_t uncache_after);
int th_widths(th_search *h, uint8_t *out);
int th_start(th_search *h);
int th_wait(th_search *h, int ms);
void th_request_stop(th_search *h);
void th_progress(th_search *h, int64_t *out);
void th_sizes(th_search *h, int64_t *out);
int th_assemble(th_search *h, cs_store *store, int64_t *offsets, int32_t *dst, void *bes, int be16,
                int32_t *parent, int32_t *parent_be);
void th_free(th_search *h);
/* cffi: end */

#endif
