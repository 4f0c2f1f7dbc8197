/* Lesson 07, stage 4: the whole scene (llvmpipe's lp_rast.c): set-up and
 * binning of every triangle, then workers taking tiles. Tiles do not
 * overlap and a tile's bin keeps scene order, so the picture is the same
 * bytes for any number of threads. */
#define _POSIX_C_SOURCE 200809L     /* pthreads, sysconf */
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <unistd.h>

#include "tiles.h"

/* A run over one scene: the set-up records, one bin per chunk of triangles
 * per tile, and the next tile nobody has taken. */
struct run {
    const struct scene *s;
    const struct raster_params *p;
    struct target *fb;
    struct tiles_options o;
    draw_fn draw;
    struct grid g;
    int threads, nchunks;       /* workers; shares of the scene (SHARES_PER_THREAD each) */
    struct bin *bins;           /* nchunks x g.n, chunk-major */
    atomic_int next_chunk;
    atomic_int next_tile;
    atomic_bool failed;
    uint8_t *thread_of;         /* per tile: the worker that drew it, or NULL */
    /* every share binned: chunks_done == nchunks, announced under the lock */
    pthread_mutex_t lock;
    pthread_cond_t binned;
    int chunks_done;
};

/* Set-up and binning of chunk `c`: a contiguous share of the scene, so that
 * chunk 0's bins then chunk 1's hold every tile's triangles in scene order. */
static void bin_chunk(struct run *r, int c)
{
    int n = r->s->ntris;
    int lo = (int)((int64_t)n * c / r->nchunks), hi = (int)((int64_t)n * (c + 1) / r->nchunks);
    struct bin *bins = r->bins + (size_t)c * (size_t)r->g.n;
    for (int i = lo; i < hi; i++) {
        struct tri_setup t;
        struct tri rec;
        if (!tri_setup_bits(&t, r->s->tris[i].v, r->s->w, r->s->h, r->p->subpixel_bits))
            continue;
        tri_record(&rec, &t, r->p->checker);
        if (!bin_triangle(&rec, &r->g, bins, r->o.corners)) {
            atomic_store(&r->failed, true);
            return;
        }
    }
}

/* Draw one tile: load it, every chunk's bin in order, store it. */
static void draw_tile(struct run *r, int tile, int worker, struct tile_buf *buf)
{
    bool empty = true;
    for (int c = 0; c < r->nchunks && empty; c++)
        empty = !r->bins[(size_t)c * (size_t)r->g.n + (size_t)tile].first;
    if (empty)
        return;
    if (r->thread_of)
        r->thread_of[tile] = (uint8_t)worker;
    struct rect rc = tile_rect(&r->g, tile);
    struct dst d = r->o.tile_buffers ? tile_load(buf, r->fb, rc) : target_dst(r->fb, rc);
    for (int k = 0; k < r->nchunks; k++) {
        /* the exhibit starts with the worker's own shares: order depends on who took the tile */
        int c = r->o.unordered ? (k + worker * SHARES_PER_THREAD) % r->nchunks : k;
        struct bin *b = &r->bins[(size_t)c * (size_t)r->g.n + (size_t)tile];
        for (const struct bin_block *blk = b->first; blk; blk = blk->next)
            for (uint32_t e = 0; e < blk->n; e++)
                r->draw(&blk->rec[e], rc, blk->rec[e].full, &d, NULL, r->o.corners == CORNERS_FOUR);
        bin_free(b);    /* here, on every worker, while its blocks are in cache */
    }
    if (r->o.tile_buffers)
        tile_store(buf, r->fb, rc);
}

struct worker {
    struct run *r;
    int id;
};

static void *work(void *arg)
{
    struct worker *w = arg;
    struct run *r = w->r;
    /* set-up and binning: shares taken one at a time, so that a worker the
     * system puts to sleep for a while holds up no more than one share */
    for (int c; (c = atomic_fetch_add(&r->next_chunk, 1)) < r->nchunks;) {
        bin_chunk(r, c);
        pthread_mutex_lock(&r->lock);
        if (++r->chunks_done == r->nchunks)
            pthread_cond_broadcast(&r->binned);
        pthread_mutex_unlock(&r->lock);
    }
    /* no tile before every share is binned: its bins are not complete */
    pthread_mutex_lock(&r->lock);
    while (r->chunks_done < r->nchunks)
        pthread_cond_wait(&r->binned, &r->lock);
    pthread_mutex_unlock(&r->lock);
    if (atomic_load(&r->failed))
        return NULL;
    struct tile_buf *buf = r->o.tile_buffers ? aligned_alloc(32, sizeof *buf) : NULL;
    if (r->o.tile_buffers && !buf) {
        atomic_store(&r->failed, true);
        return NULL;
    }
    for (;;) {
        int tile = atomic_fetch_add(&r->next_tile, 1);
        if (tile >= r->g.n)
            break;
        draw_tile(r, tile, w->id, buf);
    }
    free(buf);
    return NULL;
}

int default_threads(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > MAX_THREADS ? MAX_THREADS : (int)n;
}

/* Draw the whole scene; `thread_of` (one byte per tile, or NULL) receives
 * the worker that drew each tile. Returns false when out of memory (the
 * target may then hold part of the scene). */
bool draw_scene(const struct scene *s, const struct raster_params *p, struct target *fb,
                       struct tiles_options o, uint8_t *thread_of)
{
    if (o.no_bins) {    /* for the measurement: what binning saves */
        for (int i = 0; i < s->ntris; i++) {
            struct tri_setup t;
            tri_setup_bits(&t, s->tris[i].v, s->w, s->h, p->subpixel_bits);
            rasterize_one_tri(&t, p, fb, NULL, o);
        }
        return true;
    }
    struct run *r = calloc(1, sizeof *r);
    if (!r)
        return false;
    int threads = o.threads > 0 ? o.threads : p->threads > 0 ? p->threads : default_threads();
    threads = threads > MAX_THREADS ? MAX_THREADS : threads;
    r->s = s, r->p = p, r->fb = fb, r->o = o;
    r->draw = pick_twin(o.twin);
    r->g = grid_of(fb->w, fb->h);
    r->threads = threads;
    r->nchunks = shares(threads);
    r->thread_of = thread_of;
    atomic_init(&r->next_tile, 0);
    atomic_init(&r->next_chunk, 0);
    atomic_init(&r->failed, false);
    r->bins = calloc((size_t)r->nchunks * (size_t)r->g.n, sizeof *r->bins);
    bool ok = r->bins;
    pthread_t tid[MAX_THREADS];
    struct worker w[MAX_THREADS];
    int started = 1;
    bool sync = ok && pthread_mutex_init(&r->lock, NULL) == 0;
    if (sync && pthread_cond_init(&r->binned, NULL) != 0) {
        pthread_mutex_destroy(&r->lock);
        sync = false;
    }
    ok = ok && sync;
    if (ok) {
        for (int i = 0; i < threads; i++)
            w[i] = (struct worker){ r, i };
        /* a worker that cannot be started is no harm: the others take its
         * shares and tiles */
        for (; started < threads; started++)
            if (pthread_create(&tid[started], NULL, work, &w[started]) != 0)
                break;
        work(&w[0]);
        for (int i = 1; i < started; i++)
            pthread_join(tid[i], NULL);
        pthread_cond_destroy(&r->binned);
        pthread_mutex_destroy(&r->lock);
        ok = !atomic_load(&r->failed);
    }
    /* the workers gave back the bins of the tiles they drew; what is left
     * (a run that ran out of memory) goes back here */
    for (size_t b = 0; r->bins && b < (size_t)r->nchunks * (size_t)r->g.n; b++)
        bin_free(&r->bins[b]);
    free(r->bins);
    free(r);
    return ok;
}

/* --- one triangle through the same pipeline (tests, the narrated replay) -- */

/* The triangle binned, then drawn tile by tile in place: the same decisions
 * as the scene run, narrated. p->tile > 0 restricts it to tile p->tile - 1
 * (the narrated replay's units, see lesson.h). */
void rasterize_one_tri(const struct tri_setup *ts, const struct raster_params *p,
                              struct target *fb, struct trace *tr, struct tiles_options o)
{
    NARRATE(tr, .kind = TRACE_SETUP, .line = L_SETUP, .x = ts->minx, .y = ts->miny,
            .x1 = ts->maxx, .y1 = ts->maxy, .e = { ts->area2, 0, 0 });
    if (ts->empty)
        return;
    struct tri t;
    tri_record(&t, ts, p->checker);
    draw_fn draw = pick_twin(o.twin);
    struct grid g = grid_of(fb->w, fb->h);
    for (int ty = t.miny / TILE; ty <= t.maxy / TILE; ty++)
        for (int tx = t.minx / TILE; tx <= t.maxx / TILE; tx++) {
            int tile = ty * g.nx + tx;
            if (p->tile > 0 && tile != p->tile - 1)
                continue;
            struct rect rc = tile_rect(&g, tile);
            enum block_class k = classify_rect(&t, rc, o.corners);
            NARRATE(tr, .kind = TRACE_BLOCK,
                    .line = k == BLOCK_EMPTY ? L_REJECT : k == BLOCK_FULL ? L_FULL_TILE : L_PARTIAL_TILE,
                    .x = rc.x0, .y = rc.y0, .x1 = rc.x0 + rc.w - 1, .y1 = rc.y0 + rc.h - 1,
                    .klass = (uint8_t)k, .aux = { TILE, 0, (float)p->bin_size, (float)p->bin_entry,
                                                 (float)p->thread },
                    .mask = { corner_bits(&t, 0, rc.x0, rc.y0, rc.x0 + rc.w - 1, rc.y0 + rc.h - 1),
                              corner_bits(&t, 1, rc.x0, rc.y0, rc.x0 + rc.w - 1, rc.y0 + rc.h - 1),
                              corner_bits(&t, 2, rc.x0, rc.y0, rc.x0 + rc.w - 1, rc.y0 + rc.h - 1) });
            if (k == BLOCK_EMPTY || frozen(tr))
                continue;
            struct dst d = target_dst(fb, rc);
            draw(&t, rc, k == BLOCK_FULL, &d, tr, o.corners == CORNERS_FOUR);
        }
}

