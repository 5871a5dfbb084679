// The flat sweep (flat_sweep/render_flat_sweep.h): eye rays by row, hits shaded in
// vector packets gathered in tiles (4x4 with 16 lanes, 2x4 with 8), rows to the file as they finish.
#include "raytracer/flat_sweep/render_flat_sweep.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <utility>
#include <vector>

#include "raytracer/flat_sweep/eye_rays.h"
#include "raytracer/flat_sweep/packet_tracer.h"
#include "raytracer/helper_pool.h"
#include "raytracer/own_cache_lines.h"
#include "raytracer/row_ring.h"

namespace rt {

#ifndef RAYTRACER_EXTRA_PRECISIONS  // (see the end of this file)
bool lengths_fit_the_flat_sweep(const Scene& scene) {
    auto fits = [](double x) {
        const double a = std::abs(x);
        return a == 0 || (a >= kFlatSweepSmallest && a <= kFlatSweepLargest);
    };
    auto all_fit = [&](const Vec3<double>& v) { return fits(v.x) && fits(v.y) && fits(v.z); };
    if (!(fits(scene.near_plane) && fits(scene.left) && fits(scene.right) && fits(scene.bottom) &&
          fits(scene.top)))
        return false;
    for (const SphereSpec& s : scene.spheres)
        if (!all_fit(s.centre) || !all_fit(s.scale)) return false;
    for (const LightSpec& l : scene.lights)
        if (!all_fit(l.position)) return false;
    return true;
}
#endif

namespace {
// An ellipsoid that some pixels of a row may see, and which columns.
struct Span {
    std::uint32_t ellipsoid;
    int first, last;
};

// Eye-ray hits on one ellipsoid waiting to be shaded together.
template <typename Real>
struct Packet {
    int count = 0;
    Real dx[kPacket], dy[kPacket], dz[kPacket], t[kPacket];
    bool inside[kPacket];
    std::uint8_t* out[kPacket];

    void add(Real x, Real y, Real z, Real root, bool in, std::uint8_t* pixel) {
        dx[count] = x, dy[count] = y, dz[count] = z, t[count] = root, inside[count] = in, out[count] = pixel;
        ++count;
    }
    void shade(const PacketTracer<Real>& tracer, std::uint32_t ellipsoid, TraceScratch<Real>& scratch) {
        if (count == 0) return;
        tracer.eye_hit_pixels(ellipsoid, count, dx, dy, dz, t, inside, scratch, out);
        count = 0;
    }
};

// Eye-ray hits are gathered into packets tile by tile: kTileRows rows by kTileColumns
// columns, one packet's worth. WHY: a packet of pixels that lie close together in both
// directions mirrors rays that stay together (they split into fewer, fuller packets at
// each bounce), and its points lie in a smaller ball (LightCones rules out more spheres
// for the whole packet). Measured on the heavy scene, one thread, medians of 21
// interleaved runs: rows of 16 pixels 100.2 ms, tiles of 4 x 4 80.9 ms; instructions
// with 8 lanes (x86-64-v3, callgrind): 1 x 8 858M, 2 x 4 818M, 4 x 2 825M, 8 x 1 894M.
constexpr int kTileRows = kPacket >= 16 ? 4 : 2;
constexpr int kTileColumns = kPacket / kTileRows;

// One thread's working memory, so that no row or pixel allocates, on cache lines of its
// own (own_cache_lines.h): its blocks, and its vectors' own pointers, written every row.
template <typename Real>
struct alignas(OwnCacheLines<char>::kLine) Workspace {
    TraceScratch<Real> scratch;
    OwnLinesVector<Span> in_row;            // the row's ellipsoids
    OwnLinesVector<EyeRowHits<Real>> hits;  // per row of a band: each column's nearest hit (eye_rays.h)
    OwnLinesVector<Packet<Real>> packets;   // per ellipsoid
    OwnLinesVector<std::uint32_t> seen;     // the ellipsoids some row of the band may see (repeats allowed)

    Workspace(const PacketTracer<Real>& tracer, std::size_t ellipsoids, int columns)
        : scratch(tracer.make_scratch()), hits(kTileRows, EyeRowHits<Real>(columns)), packets(ellipsoids) {
        in_row.reserve(ellipsoids);
        seen.reserve(ellipsoids * kTileRows);
    }
};

// By default the other cores are called in only when the rest of the image would take
// the calling thread longer than this alone (see sweep_rows()). Calling a helper costs this
// thread about 0.08 ms; where it starts on an idle core at once (helper_pool.h) it
// draws rows about 0.1 ms later, where it waits for the scheduler to move it, 3 ms.
// The earlier the call, the more of the image the helper shares: 100 us rather than
// 400 us took 0.1 to 0.2 ms off the course scenes at 400x400 (testIllum, testReflection,
// testAmbient, testShadow: medians of 21 to 25 interleaved runs; 200 us in between) and
// left testBehind, which traces nothing, as it was.
std::chrono::microseconds worth_helping() {
    return std::chrono::microseconds(HelperPool::starts_on_idle_core() ? 100 : 3000);
}

// The camera's terms per ellipsoid, for intersecting eye rays many columns at a time.
template <typename Real>
EyeRays<Real> make_eye_rays(const PacketTracer<Real>& tracer, const std::vector<PixelRect>& rects,
                            const std::vector<Real>& column_x) {
    std::vector<Ellipsoid<Real>> ellipsoids;
    std::vector<MappedOrigin<Real>> eye_origins;
    std::vector<int> first_columns, last_columns;
    for (std::size_t i = 0; i < rects.size(); ++i) {
        ellipsoids.push_back(tracer.ellipsoid(i));
        eye_origins.push_back(tracer.eye_origin(i));
        first_columns.push_back(rects[i].first_column);
        last_columns.push_back(rects[i].last_column);
    }
    return EyeRays<Real>(ellipsoids, eye_origins, column_x, first_columns, last_columns);
}

// One image through the flat sweep: what every band of rows shares, made once, and the
// rows handed out a band of kTileRows at a time from a shared counter, so that a thread
// that draws cheap rows (background) takes more of them, and at the end the calling
// thread waits for at most one band of a helper's.
//
// Every pixel is a pure function of the scene and its (column, row): no state carries
// from one pixel to the next that could change a value (the last-occluder memory in the
// scratch only reorders tests whose answer is a yes/no "any"). So the image is
// byte-identical whichever thread renders which rows.
template <typename Real>
class FlatSweep {
public:
    FlatSweep(const Scene& scene, PacketTracer<Real>&& tracer, RowSink& sink, unsigned most_threads)
        : scene_(scene),
          tracer_(std::move(tracer)),
          spans_(tracer_.row_spans(scene)),
          background_row_(bytes_of_pixels(scene.columns)),
          ring_(sink, scene.rows, background_row_.size(), kTileRows, most_threads),
          column_x_(column_xs<Real>(scene)),
          eye_rays_(make_eye_rays(tracer_, tracer_.screen_rects(), column_x_)),
          near_z_(-static_cast<Real>(scene.near_plane)) {
        // Each row starts as a copy of a background row, written by the thread that
        // renders the row, and only traced pixels are written over: most pixels of the
        // course scenes see no ellipsoid (against rows zero-filled, then written pixel by
        // pixel: 0.47 M instructions less a course scene).
        std::uint8_t background[kBytesPerPixel];
        pixel_bytes(tracer_.background(), background);
        for (std::size_t i = 0; i < background_row_.size(); ++i)
            background_row_[i] = background[i % kBytesPerPixel];
    }

    // Whether some eye ray may see an ellipsoid (PacketTracer::sees_any()).
    bool sees_any() const { return tracer_.sees_any(); }

    Workspace<Real> workspace() const {
        return Workspace<Real>(tracer_, tracer_.screen_rects().size(), scene_.columns);
    }

    // Renders bands until none is left; after_band(r) after each, r its last row.
    template <typename AfterBand>
    void take_rows(Workspace<Real>& work, AfterBand after_band) {
        for (int r = next_row_.fetch_add(kTileRows); r < scene_.rows; r = next_row_.fetch_add(kTileRows)) {
            const int end = std::min(r + kTileRows, scene_.rows);
            ring_.reserve(end);
            Band band;
            band.first_row = r, band.end_row = end, band.band_lo = scene_.columns;
            if (!ring_.sink_failed()) {
                work.seen.clear();
                for (int row = r; row < end; ++row) eye_hits(row, band, work);
                shade(band, work);
            }
            for (int f = r; f < end; ++f) ring_.finish(f);
            after_band(end - 1);
        }
    }

    // Every row is finished: the rest to the sink.
    void flush() { ring_.flush(); }

private:
    // A band of at most kTileRows rows: per row, the columns some ellipsoid may cover and
    // its y; and those columns over the band.
    struct Band {
        int first_row = 0, end_row = 0;
        int lo[kTileRows] = {}, hi[kTileRows] = {};
        Real y[kTileRows] = {};
        int band_lo = 0, band_hi = -1;
    };

    // Row r as background, and the nearest hit of each of its eye rays that some
    // ellipsoid may meet (screen_bounds.h: a pixel that none may meet is the background,
    // without tracing), all columns of each ellipsoid's span at once (eye_rays.h).
    void eye_hits(int r, Band& band, Workspace<Real>& work) {
        OwnLinesVector<Span>& in_row = work.in_row;
        std::copy(background_row_.begin(), background_row_.end(), ring_.row(r));
        in_row.clear();
        int lo = scene_.columns, hi = -1;  // the columns some ellipsoid may cover
        const double row_y_double = pixel_y(scene_.top, scene_.bottom, r, scene_.rows);
        const std::vector<PixelRect>& rects = tracer_.screen_rects();
        for (std::uint32_t i = 0; i < rects.size(); ++i) {
            Span span{i, rects[i].first_column, rects[i].last_column};
            if (rects[i].first_row <= r && r <= rects[i].last_row &&
                spans_.narrow(i, row_y_double, span.first, span.last)) {
                in_row.push_back(span);
                lo = std::min(lo, span.first);
                hi = std::max(hi, span.last);
            }
        }
        const Real y = pixel_y(Real(scene_.top), Real(scene_.bottom), r, scene_.rows);
        const int b = r - band.first_row;
        EyeRowHits<Real>& hits = work.hits[static_cast<std::size_t>(b)];
        EyeRays<Real>::clear(hits, lo, hi);
        for (const Span& span : in_row) {
            eye_rays_.intersect(hits, span.ellipsoid, span.first, span.last, column_x_.data(), y, near_z_);
            work.seen.push_back(span.ellipsoid);
        }
        band.lo[b] = lo, band.hi[b] = hi, band.y[b] = y;
        band.band_lo = std::min(band.band_lo, lo), band.band_hi = std::max(band.band_hi, hi);
    }

    // The band's hit pixels, shaded in packets of pixels that see the same ellipsoid
    // (PacketTracer::eye_hit_pixels(), vector lanes), gathered tile by tile.
    void shade(const Band& band, Workspace<Real>& work) {
        for (int c0 = band.band_lo; c0 <= band.band_hi; c0 += kTileColumns)
            for (int r = band.first_row; r < band.end_row; ++r) {
                const int b = r - band.first_row;
                const EyeRowHits<Real>& hits = work.hits[static_cast<std::size_t>(b)];
                std::uint8_t* const row_out = ring_.row(r);
                const int c_end = std::min(c0 + kTileColumns - 1, band.hi[b]);
                for (int c = std::max(c0, band.lo[b]); c <= c_end; ++c) {
                    const auto column = static_cast<std::size_t>(c);
                    const std::uint32_t i = hits.ellipsoid[column];
                    if (i == kNoEllipsoid) continue;  // the background
                    // An ambient-only surface's bytes are known: no packet.
                    if (const std::uint8_t* bytes = tracer_.ambient_only_bytes(i)) {
                        std::copy(bytes, bytes + kBytesPerPixel, row_out + bytes_of_pixels(c));
                        continue;
                    }
                    Packet<Real>& packet = work.packets[i];
                    packet.add(column_x_[column], band.y[b], near_z_, hits.t[column],
                               hits.inside[column] != 0, row_out + bytes_of_pixels(c));
                    if (packet.count == kPacket) packet.shade(tracer_, i, work.scratch);
                }
            }
        for (const std::uint32_t i : work.seen) work.packets[i].shade(tracer_, i, work.scratch);
    }

    const Scene& scene_;
    const PacketTracer<Real> tracer_;
    const RowSpans<typename PacketTracer<Real>::C> spans_;  // per ellipsoid, the columns of a row
    std::vector<std::uint8_t> background_row_;
    // Rows go to the sink from a ring of rows as they are finished (row_ring.h), written
    // by whichever thread completes a block of them while no block is being written.
    // WHY: writing a 400x400 image took the calling thread 0.3-0.4 ms after the render
    // (the kernel's copy into the page cache); a block written by one thread while the
    // other renders costs the image half of that.
    RowRing ring_;
    const std::vector<Real> column_x_;
    const EyeRays<Real> eye_rays_;
    Real near_z_;
    std::atomic<int> next_row_{0};
};

// The image of a sweep that can_render(), on threads as render_to() takes them.
template <typename Real>
void sweep_rows(FlatSweep<Real>& sweep, const Scene& scene, unsigned threads, unsigned most_threads) {
    // Each helper's working memory is made here, so that a helper thread allocates
    // nothing (its first allocation would set up a malloc arena of its own).
    OwnLinesVector<Workspace<Real>> helper_work;
    auto help = [&](unsigned h) { sweep.take_rows(helper_work[h], [](int) {}); };
    HelperPool::Job helpers;  // declared after all that help uses: closed first
    auto call_helpers = [&](unsigned count) {
        const unsigned wanted = std::min<unsigned>(count, static_cast<unsigned>(scene.rows)) - 1;
        helper_work.reserve(wanted);  // no reallocation: the helpers hold references
        for (unsigned h = 0; h < wanted; ++h) helper_work.push_back(sweep.workspace());
        helpers.start(wanted, help);
    };
    // By default (threads = 0) the calling thread starts alone and calls in the other
    // cores only when, at its pace so far, the rest of the image would take it longer
    // than worth_helping(): scenes with few lit pixels are done sooner than a second
    // thread pays (measured in docs/speed.md). An image in which no eye ray can meet an
    // ellipsoid is drawn alone from the start: its rows are copies of the background, and
    // rows go to the sink one write at a time, so a helper would only wait its turn
    // (testBehind at 400x400, whole process, interleaved, medians of 300: 1.23 ms against
    // 1.36 ms with the helper its pace called in).
    if (threads > 1) call_helpers(threads);
    bool helpers_decided = threads != 0 || !sweep.sees_any();  // asked for, judged, or of no use
    Workspace<Real> work = sweep.workspace();
    const auto start = std::chrono::steady_clock::now();
    const auto worth = worth_helping();
    sweep.take_rows(work, [&](int r) {
        if (helpers_decided) return;
        // Alone, this thread has done rows 0..r. Not judged on its first eighth of
        // worth_helping() (cold caches): a scene done by then never asks.
        const int done = r + 1, left = scene.rows - done;
        const auto elapsed = std::chrono::steady_clock::now() - start;
        if (left > 0 && elapsed * 8 >= worth && elapsed * left >= worth * done) {
            helpers_decided = true;
            if (most_threads > 1)
                call_helpers(std::min<unsigned>(most_threads, static_cast<unsigned>(left + 1)));
        }
    });
    helpers.finish();
    sweep.flush();
}
}  // namespace

template <typename Real>
bool render_flat_sweep_to(const Scene& scene, RowSink& sink, unsigned threads) {
    if constexpr (kFlatSweepPrecision<Real>) {
        PacketTracer<Real> tracer(scene);
        if (!tracer.can_render()) return false;  // its tables freed before the tree is built
        const unsigned most_threads = threads_asked(threads);
        FlatSweep<Real> sweep(scene, std::move(tracer), sink, most_threads);
        sweep_rows(sweep, scene, threads, most_threads);
        return true;
    }
    return false;
}

// As render.cpp: double for raytracer.exe, float and long double for the tests.
#ifdef RAYTRACER_EXTRA_PRECISIONS
template bool render_flat_sweep_to<float>(const Scene&, RowSink&, unsigned);
template bool render_flat_sweep_to<long double>(const Scene&, RowSink&, unsigned);
#else
template bool render_flat_sweep_to<double>(const Scene&, RowSink&, unsigned);
#endif

}  // namespace rt
