/* Lesson 07, stage 4: the whole scene (llvmpipe's lp_rast.c). The scene is
 * cut into shares; workers take shares, set up and bin their triangles, then
 * take tiles, each drawn from its bins in the worker's tile buffer and stored
 * once. Tiles do not overlap and a tile's bins keep scene order, so the
 * picture is the same bytes for any number of threads.
 *
 * Narrated (the explorer's run), the workers take their turns one after
 * another, worker 0, 1, ... and round again, each turn one share or one
 * tile: the same code, in an order that every run repeats. */
#define _POSIX_C_SOURCE 200809L     /* pthreads, sysconf */
#include <pthread.h>
#include <sched.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tiles.h"

/* --- memory kept from one run to the next ---------------------------------
 *
 * The records of the scene's triangles, the bins, and each worker's arena
 * and tile buffer, reused by every run: fresh memory costs a page fault per
 * 4 KB. One run at a time per build (the frame lock); each worker's part on
 * lines of its own. */
static pthread_mutex_t frame_lock = PTHREAD_MUTEX_INITIALIZER;

struct worker_mem {
    _Alignas(CACHE_LINE) struct arena arena;
    struct tile_buf *buf;
};

static struct {
    struct tri *records;
    size_t nrecords;
    struct bin *bins;
    size_t nbins;
    struct worker_mem mem[MAX_THREADS];
} kept;

/* Room for n records, nbins bins (emptied) and `workers` arenas (emptied)
 * and tile buffers; false when out of memory. Under the frame lock. */
static bool keep_room(size_t n, size_t nbins, int workers, bool buffers)
{
    if (n > kept.nrecords) {
        free(kept.records);
        kept.nrecords = 0;
        if (!(kept.records = malloc(n * sizeof *kept.records)))
            return false;
        kept.nrecords = n;
    }
    if (nbins > kept.nbins) {
        free(kept.bins);
        kept.nbins = 0;
        if (!(kept.bins = malloc(nbins * sizeof *kept.bins)))
            return false;
        kept.nbins = nbins;
    }
    memset(kept.bins, 0, nbins * sizeof *kept.bins);
    for (int w = 0; w < workers; w++) {
        arena_reset(&kept.mem[w].arena);
        if (buffers && !kept.mem[w].buf
            && !(kept.mem[w].buf = aligned_alloc(CACHE_LINE, sizeof *kept.mem[w].buf)))
            return false;
    }
    return true;
}

/* --- a run ----------------------------------------------------------------- */

struct run {
    const struct scene *s;      /* NULL: one triangle, records[0] */
    const struct raster_params *p;
    struct target *fb;
    struct tiles_options o;
    draw_fn draw;
    struct grid g;
    int threads, nshares;
    struct tri *records;        /* one per triangle of the scene */
    struct bin *bins;           /* nshares x g.n, share-major */
    struct trace *tr;           /* narrated: the workers take turns */
    /* the narration of part of a bin (a step of the replay): its first
     * entry's place in the whole bin, and the whole bin's size; -1: all */
    int first_entry, bin_size;
    /* what the workers share, each counter on a line of its own */
    _Alignas(CACHE_LINE) atomic_int next_share;
    _Alignas(CACHE_LINE) atomic_int shares_done;
    _Alignas(CACHE_LINE) atomic_int next_tile;
    _Alignas(CACHE_LINE) atomic_bool failed;
};

/* Set-up and binning of share c: a contiguous part of the scene, so that
 * share 0's bins then share 1's hold every tile's triangles in scene order. */
static void bin_share(struct run *r, int c, int worker)
{
    int n = r->s->ntris;
    int lo = (int)((int64_t)n * c / r->nshares), hi = (int)((int64_t)n * (c + 1) / r->nshares);
    struct bin *bins = r->bins + (size_t)c * (size_t)r->g.n;
    for (int i = lo; i < hi; i++) {
        struct tri_setup t;
        if (NARRATING && r->tr)
            r->tr->tri = (uint32_t)i;
        tri_setup_bits(&t, r->s->tris[i].v, r->s->w, r->s->h, r->p->subpixel_bits);
        if (!tri_set_up(&r->records[i], &t, r->p->checker, r->tr))
            continue;
        if (!bin_triangle(&r->records[i], (uint32_t)i, &r->g, bins, &kept.mem[worker].arena,
                          r->o.corners, r->tr)) {
            atomic_store(&r->failed, true);
            return;
        }
    }
}

/* The bin of tile `tile` from share c. */
static const struct bin *bin_of(const struct run *r, int c, int tile)
{
    return &r->bins[(size_t)c * (size_t)r->g.n + (size_t)tile];
}

/* The shares in the order a tile's worker draws them: scene order, except
 * in the exhibit, which starts with the worker's own shares. */
static int share_at(const struct run *r, int k, int worker)
{
    return r->o.unordered ? (k + worker * SHARES_PER_THREAD) % r->nshares : k;
}

/* Draw one tile: load the part its bins may touch, every share's bin in
 * order, store it once. */
static void draw_tile(struct run *r, int tile, int worker, struct tile_buf *buf)
{
    struct rect rc = tile_rect(&r->g, tile);
    int x0 = rc.x0 + rc.w, y0 = rc.y0 + rc.h, x1 = rc.x0 - 1, y1 = rc.y0 - 1, size = 0;
    for (int c = 0; c < r->nshares; c++)
        for (const struct bin_block *b = bin_of(r, c, tile)->first; b; b = b->next)
            for (uint32_t e = 0; e < b->n; e++) {
                const struct tri *t = &r->records[b->entry[e] >> 1];
                x0 = t->minx < x0 ? t->minx : x0, y0 = t->miny < y0 ? t->miny : y0;
                x1 = t->maxx > x1 ? t->maxx : x1, y1 = t->maxy > y1 ? t->maxy : y1;
                size++;
            }
    if (!size)
        return;
    x0 = x0 < rc.x0 ? rc.x0 : x0, y0 = y0 < rc.y0 ? rc.y0 : y0;
    x1 = x1 > rc.x0 + rc.w - 1 ? rc.x0 + rc.w - 1 : x1, y1 = y1 > rc.y0 + rc.h - 1 ? rc.y0 + rc.h - 1 : y1;
    struct rect part = { x0, y0, x1 - x0 + 1, y1 - y0 + 1 };
    int first = r->first_entry >= 0 ? r->first_entry : 0;
    int whole = r->bin_size >= 0 ? r->bin_size : size;
    struct trace *tr = r->tr;
    (void)whole;    /* the fast build compiles the narration out */
    if (first == 0)
        NARRATE(tr, .kind = TRACE_BLOCK, .line = L_TAKE, .x = rc.x0, .y = rc.y0,
                .x1 = rc.x0 + rc.w - 1, .y1 = rc.y0 + rc.h - 1, .klass = BLOCK_CLASS_COUNT,
                .aux = { TILE, 0, (float)whole, 0, (float)worker });
    struct dst d = r->o.tile_buffers ? tile_load(buf, r->fb, rc, part) : target_dst(r->fb, rc);
    int entry = first;
    for (int k = 0; k < r->nshares && !frozen(tr); k++)
        for (const struct bin_block *b = bin_of(r, share_at(r, k, worker), tile)->first; b; b = b->next)
            for (uint32_t e = 0; e < b->n && !frozen(tr); e++, entry++) {
                uint32_t index = b->entry[e] >> 1;
                bool full = b->entry[e] & 1;
                if (NARRATING && tr && r->s)
                    tr->tri = index;
                NARRATE(tr, .kind = TRACE_BLOCK, .line = full ? L_FULL_TILE : L_BIN_LOOP,
                        .x = rc.x0, .y = rc.y0, .x1 = rc.x0 + rc.w - 1, .y1 = rc.y0 + rc.h - 1,
                        .klass = full ? BLOCK_FULL : BLOCK_CLASS_COUNT,
                        .aux = { TILE, 0, (float)whole, (float)entry, (float)worker });
                r->draw(&r->records[index], rc, full, &d, tr, r->o.corners == CORNERS_FOUR);
            }
    if (entry == whole)
        NARRATE(tr, .kind = TRACE_BLOCK, .line = L_STORE, .x = part.x0, .y = part.y0,
                .x1 = part.x0 + part.w - 1, .y1 = part.y0 + part.h - 1, .klass = BLOCK_CLASS_COUNT,
                .aux = { TILE, 0, (float)whole, (float)(whole - 1), (float)worker });
    /* stored even when the narration stops inside the tile: the explorer
     * shows the tile buffer as it stands */
    if (r->o.tile_buffers)
        tile_store(buf, r->fb, rc, part);
}

/* One turn of worker `id`: a share to bin, or, once every share is binned,
 * a tile to draw. False when nothing is left. */
static bool work_step(struct run *r, int id)
{
    if (atomic_load(&r->next_share) < r->nshares) {
        int c = atomic_fetch_add(&r->next_share, 1);
        if (c < r->nshares) {
            bin_share(r, c, id);
            atomic_fetch_add(&r->shares_done, 1);
            return true;
        }
    }
    /* no tile before every share is binned: its bins are not complete */
    while (atomic_load(&r->shares_done) < r->nshares)
        sched_yield();
    if (atomic_load(&r->failed))
        return false;
    int tile = atomic_fetch_add(&r->next_tile, 1);
    if (tile >= r->g.n)
        return false;
    draw_tile(r, tile, id, kept.mem[id].buf);
    return true;
}

struct worker {
    struct run *r;
    int id;
};

static void *work(void *arg)
{
    struct worker *w = arg;
    while (work_step(w->r, w->id))
        ;
    return NULL;
}

/* The workers, the caller among them; narrated, one turn at a time. */
static void run_workers(struct run *r)
{
    if (NARRATING && r->tr) {
        for (bool more = true; more;) {
            more = false;
            for (int w = 0; w < r->threads; w++)
                more = work_step(r, w) || more;
        }
        return;
    }
    pthread_t tid[MAX_THREADS];
    struct worker w[MAX_THREADS];
    int started = 1;
    for (int i = 0; i < r->threads; i++)
        w[i] = (struct worker){ r, i };
    /* a worker that cannot be started is no harm: the others take its
     * shares and tiles */
    for (; started < r->threads; started++)
        if (pthread_create(&tid[started], NULL, work, &w[started]) != 0)
            break;
    work(&w[0]);
    for (int i = 1; i < started; i++)
        pthread_join(tid[i], NULL);
}

int default_threads(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > MAX_THREADS ? MAX_THREADS : (int)n;
}

static void run_init(struct run *r, const struct raster_params *p, struct target *fb,
                     const struct tiles_options *o, int threads, struct trace *tr)
{
    *r = (struct run){ .p = p, .fb = fb, .o = *o, .draw = pick_twin(o->twin),
                       .g = grid_of(fb->w, fb->h), .threads = threads, .nshares = shares(threads),
                       .records = kept.records, .bins = kept.bins, .tr = tr,
                       .first_entry = -1, .bin_size = -1 };
    atomic_init(&r->next_share, 0);
    atomic_init(&r->shares_done, 0);
    atomic_init(&r->next_tile, 0);
    atomic_init(&r->failed, false);
}

/* Draw the whole scene, narrated to tr (or not: NULL). Returns false when
 * out of memory (the target may then hold part of the scene). */
bool draw_scene(const struct scene *s, const struct raster_params *p, struct target *fb,
                struct tiles_options o, struct trace *tr)
{
    if (o.no_bins) {    /* for the measurement: what binning saves */
        for (int i = 0; i < s->ntris; i++) {
            struct tri_setup t;
            tri_setup_bits(&t, s->tris[i].v, s->w, s->h, p->subpixel_bits);
            if (NARRATING && tr)
                tr->tri = (uint32_t)i;
            if (!rasterize_one_tri(&t, p, fb, tr, o))
                return false;
        }
        return true;
    }
    int threads = o.threads > 0 ? o.threads : p->threads > 0 ? p->threads : default_threads();
    threads = threads > MAX_THREADS ? MAX_THREADS : threads;
    struct grid g = grid_of(fb->w, fb->h);
    pthread_mutex_lock(&frame_lock);
    bool ok = keep_room(s->ntris > 0 ? (size_t)s->ntris : 1,
                        (size_t)shares(threads) * (size_t)g.n, threads, o.tile_buffers);
    if (ok) {
        struct run r;
        run_init(&r, p, fb, &o, threads, tr);
        r.s = s;
        run_workers(&r);
        ok = !atomic_load(&r.failed);
    }
    pthread_mutex_unlock(&frame_lock);
    return ok;
}

/* One triangle through the same stages, on the calling thread: a scene of
 * one triangle, set up, binned, every tile of its bin drawn in the tile
 * buffer and stored. A step of the narrated replay (tiles.c) is one part
 * of the scene's run: the triangle's set-up and binning (p->tile == 0,
 * p->bin_entry < 0), or its entry in tile p->tile - 1's bin, drawn by
 * worker p->thread (the triangle set up and binned again, silently, into
 * a bin of its own). */
bool rasterize_one_tri(const struct tri_setup *ts, const struct raster_params *p,
                       struct target *fb, struct trace *tr, struct tiles_options o)
{
    bool bin_step = p->tile == 0 && p->bin_entry < 0, tile_step = p->tile > 0;
    struct grid g = grid_of(fb->w, fb->h);
    pthread_mutex_lock(&frame_lock);
    bool ok = keep_room(1, (size_t)g.n, 1, o.tile_buffers);
    struct run r;
    run_init(&r, p, fb, &o, 1, tile_step ? NULL : tr);
    struct tri *t = &r.records[0];
    if (ok && tri_set_up(t, ts, p->checker, r.tr))
        ok = bin_triangle(t, 0, &g, r.bins, &kept.mem[0].arena, o.corners, r.tr);
    if (ok && !ts->empty && !bin_step) {
        int worker = 0;
        if (tile_step) {
            r.tr = tr;
            r.first_entry = p->bin_entry, r.bin_size = p->bin_size;
            worker = p->thread;
        }
        struct tile_buf *buf = kept.mem[0].buf;
        for (int ty = t->miny / TILE; ty <= t->maxy / TILE; ty++)
            for (int tx = t->minx / TILE; tx <= t->maxx / TILE; tx++)
                if (!tile_step || ty * g.nx + tx == p->tile - 1)
                    draw_tile(&r, ty * g.nx + tx, worker, buf);
    }
    pthread_mutex_unlock(&frame_lock);
    return ok;
}
