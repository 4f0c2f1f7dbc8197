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
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "tiles.h"

/* --- memory kept from one run to the next ---------------------------------
 *
 * Each worker's arena and tile buffer, and the run's table of shares, reused
 * by every run: fresh memory costs a page fault per 4 KB. One run at a time
 * per build (the frame lock); each worker's part on lines of its own. */
static pthread_mutex_t frame_lock = PTHREAD_MUTEX_INITIALIZER;

struct worker_mem {
    _Alignas(CACHE_LINE) struct arena arena;
    struct tile_buf *buf;
};

/* A share of the scene once set up and binned: its triangles' records and
 * one bin per tile, whose entries number those records. Written by one
 * worker, then published whole; never changed after. */
struct share_out {
    int lo, hi;                 /* the triangles lo .. hi - 1 of the scene */
    struct tri *records;        /* hi - lo */
    struct bin *bins;           /* one per tile */
};

/* A share's place in the run: its result, once some worker published it,
 * and how far the worker binning it has come (every SHARE_PROGRESS
 * triangles). */
struct share {
    _Alignas(CACHE_LINE) _Atomic(struct share_out *) out;
    atomic_int progress;
};

#define SHARE_PROGRESS 64
#define STALL_NS 50000      /* no progress for 50 us: its worker is not running */

static struct {
    struct share *shares;
    int nshares;
    struct worker_mem mem[MAX_THREADS];
} kept;

/* Room for nshares shares (none published) and `workers` arenas (emptied)
 * and tile buffers; false when out of memory. Under the frame lock. */
static bool keep_room(int nshares, int workers, bool buffers)
{
    if (nshares > kept.nshares) {
        free(kept.shares);
        kept.nshares = 0;
        if (!(kept.shares = aligned_alloc(CACHE_LINE, (size_t)nshares * sizeof *kept.shares)))
            return false;
        kept.nshares = nshares;
    }
    for (int c = 0; c < nshares; c++) {
        atomic_init(&kept.shares[c].out, NULL);
        atomic_init(&kept.shares[c].progress, 0);
    }
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
    const struct scene *s;      /* the scene, or one triangle: */
    const struct tri_setup *one;
    const struct raster_params *p;
    struct target *fb;
    struct tiles_options o;
    draw_fn draw;
    struct grid g;
    int threads, nshares;
    struct share *shares;
    struct trace *tr;           /* narrated: the workers take turns */
    /* the narration of part of a bin (a step of the replay): its first
     * entry's place in the whole bin, and the whole bin's size; -1: all */
    int first_entry, bin_size;
    /* what the workers share, each counter on a line of its own */
    _Alignas(CACHE_LINE) atomic_int next_share;
    _Alignas(CACHE_LINE) atomic_int next_tile;
    _Alignas(CACHE_LINE) atomic_bool failed;
};

/* Set-up and binning of share c, a contiguous part of the scene (so that
 * share 0's bins then share 1's hold every tile's triangles in scene
 * order), into the memory of worker `worker`; then published, unless
 * another worker published it first. The share's result, or NULL when out
 * of memory. */
static const struct share_out *bin_share(struct run *r, int c, int worker)
{
    struct arena *a = &kept.mem[worker].arena;
    int n = r->s ? r->s->ntris : 1;
    struct share_out *out = arena_alloc(a, sizeof *out);
    if (!out)
        goto failed;
    out->lo = (int)((int64_t)n * c / r->nshares), out->hi = (int)((int64_t)n * (c + 1) / r->nshares);
    out->records = arena_alloc(a, (size_t)(out->hi - out->lo) * sizeof *out->records + 1);
    out->bins = arena_alloc(a, (size_t)r->g.n * sizeof *out->bins);
    if (!out->records || !out->bins)
        goto failed;
    memset(out->bins, 0, (size_t)r->g.n * sizeof *out->bins);
    for (int i = out->lo; i < out->hi; i++) {
        struct tri_setup own;
        const struct tri_setup *t = r->one;
        if (r->s) {
            if (NARRATING && r->tr)
                r->tr->tri = (uint32_t)i;
            tri_setup_bits(&own, r->s->tris[i].v, r->s->w, r->s->h, r->p->subpixel_bits);
            t = &own;
        }
        if ((i - out->lo) % SHARE_PROGRESS == SHARE_PROGRESS - 1)
            atomic_fetch_add_explicit(&r->shares[c].progress, 1, memory_order_relaxed);
        struct tri *rec = &out->records[i - out->lo];
        if ((r->o.pass ? r->o.pass->set_up(rec, t, r->p, r->tr) : tri_set_up(rec, t, r->p->checker, r->tr))
            && !bin_triangle(rec, (uint32_t)(i - out->lo), &r->g, out->bins, a, r->o.corners, r->tr))
            goto failed;
    }
    struct share_out *none = NULL;
    if (atomic_compare_exchange_strong(&r->shares[c].out, &none, out))
        return out;
    return none;        /* someone else's, the same bins */
failed:
    atomic_store(&r->failed, true);
    return NULL;
}

static long long nanoseconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (long long)t.tv_sec * 1000000000 + t.tv_nsec;
}

/* Share c's result: published, or made now. A worker waits for a share
 * that another worker is binning only while that one makes progress: when
 * it stops (the system has put it aside to run something else), the
 * worker bins the share itself, and the first to finish publishes. */
static const struct share_out *share_of(struct run *r, int c, int worker)
{
    const struct share_out *out;
    int seen = -1;
    long long since = 0;
    while (!(out = atomic_load(&r->shares[c].out)) && !atomic_load(&r->failed)) {
        int now = atomic_load_explicit(&r->shares[c].progress, memory_order_relaxed);
        if (now != seen)
            seen = now, since = nanoseconds();
        else if (nanoseconds() - since > STALL_NS)
            return bin_share(r, c, worker);
    }
    return out;
}

/* The shares in the order a tile's worker draws them: scene order, except
 * in the exhibit, which starts with the worker's own shares. */
static int share_at(const struct run *r, int k, int worker)
{
    return r->o.unordered ? (k + worker * SHARES_PER_THREAD) % r->nshares : k;
}

/* Triangle i of the scene (or the one triangle) drawn by another lesson's
 * pass: set up again from the scene, as that lesson sets it up, with its
 * image texture (lesson 09's). */
static void draw_pass(const struct run *r, int i, void *buf, struct rect rc, struct trace *tr)
{
    if (!r->s) {
        r->o.pass->draw(buf, r->one, rc, r->p, tr);
        return;
    }
    struct tri_setup t;
    tri_setup_bits(&t, r->s->tris[i].v, r->s->w, r->s->h, r->p->subpixel_bits);
    struct raster_params each = lesson_params_tri(r->p, r->s, i);
    r->o.pass->draw(buf, &t, rc, &each, tr);
}

/* Draw one tile: load it into the tile buffer, every share's bin in
 * order, store it once. */
static void draw_tile(struct run *r, int tile, int worker, struct tile_buf *buf)
{
    const struct share_out *outs[MAX_THREADS * SHARES_PER_THREAD];
    struct rect rc = tile_rect(&r->g, tile);
    int size = 0;
    for (int k = 0; k < r->nshares; k++) {
        int c = share_at(r, k, worker);
        if (!(outs[c] = share_of(r, c, worker)))
            return;
        for (const struct bin_block *b = outs[c]->bins[tile].first; b; b = b->next)
            size += (int)b->n;
    }
    if (!size)
        return;
    /* the part of the tile loaded and stored: all of it, or for one
     * triangle (a step of the replay) its box in the tile */
    struct rect part = rc;
    if (!r->s) {
        const struct tri *t = &outs[0]->records[0];
        int x0 = t->minx > rc.x0 ? t->minx : rc.x0, y0 = t->miny > rc.y0 ? t->miny : rc.y0;
        int x1 = t->maxx < rc.x0 + rc.w - 1 ? t->maxx : rc.x0 + rc.w - 1;
        int y1 = t->maxy < rc.y0 + rc.h - 1 ? t->maxy : rc.y0 + rc.h - 1;
        part = (struct rect){ x0, y0, x1 - x0 + 1, y1 - y0 + 1 };
    }
    int first = r->first_entry >= 0 ? r->first_entry : 0;
    int whole = r->bin_size >= 0 ? r->bin_size : size;
    struct trace *tr = r->tr;
    (void)whole;    /* the fast build compiles the narration out */
    if (first == 0)
        NARRATE(tr, .kind = TRACE_BLOCK, .line = L_TAKE, .x = rc.x0, .y = rc.y0,
                .x1 = rc.x0 + rc.w - 1, .y1 = rc.y0 + rc.h - 1, .klass = BLOCK_CLASS_COUNT,
                .aux = { TILE, 0, (float)whole, 0, (float)worker });
    bool pixels = !(NARRATING && r->o.order_only);
    const struct tile_pass *pass = r->o.pass;
    struct dst d = { 0 };
    void *pass_buf = NULL;
    if (pixels && pass && !(pass_buf = pass->load(worker, r->fb, rc, part))) {
        atomic_store(&r->failed, true);
        return;
    }
    if (pixels && !pass)
        d = r->o.tile_buffers ? tile_load(buf, r->fb, rc, part) : target_dst(r->fb, rc);
    int entry = first;
    for (int k = 0; k < r->nshares && !frozen(tr); k++) {
        const struct share_out *out = outs[share_at(r, k, worker)];
        for (const struct bin_block *b = out->bins[tile].first; b; b = b->next)
            for (uint32_t e = 0; e < b->n && !frozen(tr); e++, entry++) {
                const struct tri *t = &out->records[b->entry[e] >> 1];
                if (e + 4 < b->n) {     /* a record read a few triangles ahead */
                    const char *ahead = (const char *)&out->records[b->entry[e + 4] >> 1];
                    if (pass && r->s)   /* ... a pass's: the scene's triangle, set up again */
                        ahead = (const char *)&r->s->tris[out->lo + (int)(b->entry[e + 4] >> 1)];
                    __builtin_prefetch(ahead);
                    __builtin_prefetch(ahead + CACHE_LINE);
                    __builtin_prefetch(ahead + (pass ? 2 * CACHE_LINE : sizeof *t - 1));
                    __builtin_prefetch(ahead + (pass ? sizeof *r->s->tris : sizeof *t) - 1);
                }
                bool full = (b->entry[e] & 1) && !pass;
                if (NARRATING && tr && r->s)
                    tr->tri = (uint32_t)out->lo + (b->entry[e] >> 1);
                NARRATE(tr, .kind = TRACE_BLOCK, .line = full ? L_FULL_TILE : L_BIN_LOOP,
                        .x = rc.x0, .y = rc.y0, .x1 = rc.x0 + rc.w - 1, .y1 = rc.y0 + rc.h - 1,
                        .klass = full ? BLOCK_FULL : BLOCK_CLASS_COUNT,
                        .aux = { TILE, 0, (float)whole, (float)entry, (float)worker });
                if (pixels && pass)
                    draw_pass(r, out->lo + (int)(b->entry[e] >> 1), pass_buf, rc, tr);
                else if (pixels)
                    r->draw(t, rc, full, &d, tr, r->o.corners == CORNERS_FOUR);
            }
    }
    if (entry == whole)
        NARRATE(tr, .kind = TRACE_BLOCK, .line = L_STORE, .x = part.x0, .y = part.y0,
                .x1 = part.x0 + part.w - 1, .y1 = part.y0 + part.h - 1, .klass = BLOCK_CLASS_COUNT,
                .aux = { TILE, 0, (float)whole, (float)(whole - 1), (float)worker });
    /* stored even when the narration stops inside the tile: the explorer
     * shows the tile buffer as it stands */
    if (pixels && pass)
        pass->store(pass_buf, r->fb, rc, part);
    else if (r->o.tile_buffers && pixels)
        tile_store(buf, r->fb, rc, part);
}

/* One turn of worker `id`: a share to bin while some are left, then a tile
 * to draw. False when nothing is left. */
static bool work_step(struct run *r, int id)
{
    if (atomic_load(&r->failed))
        return false;
    if (atomic_load_explicit(&r->next_share, memory_order_relaxed) < r->nshares) {
        int c = atomic_fetch_add(&r->next_share, 1);
        if (c < r->nshares) {
            bin_share(r, c, id);
            return true;
        }
    }
    int tile = atomic_fetch_add(&r->next_tile, 1);
    if (tile >= r->g.n)
        return false;
    draw_tile(r, tile, id, kept.mem[id].buf);
    return true;
}

/* --- the workers: started once, woken for every run ------------------------
 *
 * Threads started for every picture cost their creation and, on a busy
 * machine, a wait until the system first runs them. Here they are started
 * once and sleep between runs. A run wakes them and the caller works too;
 * a worker that wakes late finds the run over and sleeps again, and the
 * caller waits only for workers inside the run (each holding at most one
 * tile: a share it holds, the others bin themselves). */
static struct {
    pthread_mutex_t lock;
    pthread_cond_t wake;
    unsigned long generation;   /* runs begun */
    struct run *job;            /* the run under way, or NULL */
    int started;                /* workers 1 .. started */
    _Alignas(CACHE_LINE) atomic_int inside;     /* workers inside the job */
} pool = { PTHREAD_MUTEX_INITIALIZER, PTHREAD_COND_INITIALIZER, 0, NULL, 0, 0 };

static void *worker_main(void *arg)
{
    int id = (int)(intptr_t)arg;
    unsigned long seen = 0;
    pthread_mutex_lock(&pool.lock);
    for (;;) {
        while (pool.generation == seen)
            pthread_cond_wait(&pool.wake, &pool.lock);
        seen = pool.generation;
        struct run *r = pool.job;
        if (!r || id >= r->threads)
            continue;
        atomic_fetch_add(&pool.inside, 1);
        pthread_mutex_unlock(&pool.lock);
        while (work_step(r, id))
            ;
        atomic_fetch_sub(&pool.inside, 1);
        pthread_mutex_lock(&pool.lock);
    }
    return NULL;
}

/* The workers, the caller among them (worker 0); narrated, one turn at a
 * time in a fixed order. */
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
    pthread_mutex_lock(&pool.lock);
    /* a worker that cannot be started is no harm: the others take its
     * shares and tiles */
    for (pthread_t tid; pool.started < r->threads - 1; pool.started++)
        if (pthread_create(&tid, NULL, worker_main, (void *)(intptr_t)(pool.started + 1)) != 0
            || pthread_detach(tid) != 0)
            break;
    if (r->threads > 1) {
        pool.job = r;
        pool.generation++;
        pthread_cond_broadcast(&pool.wake);
    }
    pthread_mutex_unlock(&pool.lock);
    while (work_step(r, 0))
        ;
    if (r->threads > 1) {
        pthread_mutex_lock(&pool.lock);
        pool.job = NULL;        /* no worker joins from here on */
        pthread_mutex_unlock(&pool.lock);
        while (atomic_load(&pool.inside) > 0)
            sched_yield();
    }
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
                       .shares = kept.shares, .tr = tr, .first_entry = -1, .bin_size = -1 };
    atomic_init(&r->next_share, 0);
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
    int threads = o.threads > 0 ? o.threads
                  : p->knob[P_THREADS] > 0 ? p->knob[P_THREADS] : default_threads();
    threads = threads > MAX_THREADS ? MAX_THREADS : threads;
    pthread_mutex_lock(&frame_lock);
    bool ok = keep_room(shares(threads), threads, o.tile_buffers);
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
 * buffer and stored. A step of the narrated replay (tiles.c) is one unit
 * of the scene's run (p->at->unit): the triangle's set-up and binning
 * (tile -1), or its entry in a tile's bin, drawn by the unit's worker (the
 * triangle set up and binned again, silently, into a bin of its own). */
bool rasterize_one_tri(const struct tri_setup *ts, const struct raster_params *p,
                       struct target *fb, struct trace *tr, struct tiles_options o)
{
    const struct lesson_unit *u = p->at ? p->at->unit : NULL;
    bool bin_step = u && u->tile < 0, tile_step = u && u->tile >= 0;
    pthread_mutex_lock(&frame_lock);
    bool ok = keep_room(1, 1, o.tile_buffers);
    struct run r;
    run_init(&r, p, fb, &o, 1, tile_step ? NULL : tr);
    r.one = ts;
    const struct share_out *out = ok ? bin_share(&r, 0, 0) : NULL;
    ok = ok && out;
    /* (a pass decides from its own record: samples may be covered where no
     * pixel centre is) */
    if (ok && (o.pass || !ts->empty) && !bin_step) {
        int worker = 0;
        if (tile_step) {
            r.tr = tr;
            r.first_entry = u->bin_entry, r.bin_size = u->bin_size;
            worker = u->thread;
        }
        const struct tri *t = &out->records[0];
        for (int ty = t->miny / TILE; ty <= t->maxy / TILE; ty++)
            for (int tx = t->minx / TILE; tx <= t->maxx / TILE; tx++)
                if (!tile_step || ty * r.g.nx + tx == u->tile)
                    draw_tile(&r, ty * r.g.nx + tx, worker, kept.mem[0].buf);
    }
    pthread_mutex_unlock(&frame_lock);
    return ok;
}
