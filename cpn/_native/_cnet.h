/* The run-time of the C generated from a net's inscriptions (_cnet.c): what Python calls (between the cffi
 * markers; gen_new is the generated code's own), and what the multi-threaded search (_threads.c) calls.
 *
 * The generated code (cpn/engine/ccodegen.py) is compiled right after _cnet.c, in the same library: it
 * calls _cnet.c's own helpers and _search.c's nd_put_group, and defines gen_new, gen_group and gen_add. */
#ifndef CPN_CNET_H
#define CPN_CNET_H

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "_search.h"

/* cffi: begin */
void *gen_new(void);
void gen_free(void *g);
int64_t gen_count(void *g, int what, int p);
int32_t gen_ms_len(void *g, int what, int p, int64_t id);
int32_t *gen_ms_pairs(void *g, int what, int p, int64_t id);
int64_t gen_ms_table(void *g, int what, int p, int64_t **off, int32_t **len, int32_t **pairs);
int64_t gen_ms_put(void *g, int what, int p, const int32_t *pr, int32_t n);
int64_t gen_be_key(void *g, int64_t be, int32_t *t);
int64_t gen_be_put(void *g, int t, int64_t key);
int64_t gen_node_count(void *g, int d);
int64_t gen_node_put(void *g, int d, const int64_t *x, int w);
int gen_node_get(void *g, int d, int64_t id, int64_t *x, int cap);
int gen_node_len(void *g, int d, int64_t id);
int64_t gen_tid_put(void *g, int p, int64_t col, int64_t ts);
int64_t gen_tid_table(void *g, int p, int32_t **col, int64_t **ts);
/* cffi: end */

#ifdef ND_THREADS
/* Another context over g's tables, for another thread (the tables are shared from then on), and the
 * end of their sharing once the threads are done. */
void *gen_clone(void *g);
void gen_unshare(void *g);
#endif

#endif
