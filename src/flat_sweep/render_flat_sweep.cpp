// The flat sweep (flat_sweep/render_flat_sweep.h): eye rays by row, hits shaded in
// vector packets gathered in tiles (4x4 with 16 lanes, 2x4 with 8), rows to the file as they finish.
#include "raytracer/flat_sweep/render_flat_sweep.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "raytracer/flat_sweep/eye_rays.h"
#include "raytracer/flat_sweep/packet_tracer.h"
#include "raytracer/own_cache_lines.h"
#include "raytracer/render_bands.h"

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

// Eye-ray hits on one ellipsoid waiting to be shaded together, as one packet of lanes
// (HitPacket, hit_packet.h) once kPacket have come or the band is done.
template <typename Real>
struct PendingEyeHits {
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
// columns, one packet's worth. Tiles set the order in which pixels join their
// ellipsoid's packet, not its bounds: a packet is shaded when full or at the band's end,
// so it may hold the tail of one tile and the head of the next. WHY: a packet of pixels that lie close
// together in both directions mirrors rays that stay together (they split into fewer, fuller packets at each
// bounce), and its points lie in a smaller ball (LightCones rules out more spheres for the whole packet).
// Measured on the heavy scene, one thread, medians of 21 interleaved runs: rows of 16 pixels 100.2 ms, tiles
// of 4 x 4 80.9 ms; instructions with 8 lanes (x86-64-v3, callgrind): 1 x 8 858M, 2 x 4 818M, 4 x 2 825M, 8 x
// 1 894M.
constexpr int kTileRows = kPacket >= 16 ? 4 : 2;
constexpr int kTileColumns = kPacket / kTileRows;

// One thread's working memory, so that no row or pixel allocates, on cache lines of its
// own (own_cache_lines.h): its blocks, and its vectors' own pointers, written every row.
template <typename Real>
struct alignas(OwnCacheLines<char>::kLine) Workspace {
    TraceScratch<Real> scratch;
    OwnLinesVector<Span> in_row;            // the row's ellipsoids
    OwnLinesVector<EyeRowHits<Real>> hits;  // per row of a band: each column's nearest hit (eye_rays.h)
    OwnLinesVector<PendingEyeHits<Real>> pending;  // per ellipsoid
    OwnLinesVector<std::uint32_t> seen;  // the ellipsoids some row of the band may see (repeats allowed)

    Workspace(const PacketTracer<Real>& tracer, std::size_t ellipsoids, int columns)
        : scratch(tracer.make_scratch()), hits(kTileRows, EyeRowHits<Real>(columns)), pending(ellipsoids) {
        in_row.reserve(ellipsoids);
        seen.reserve(ellipsoids * kTileRows);
    }
};

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
// drawing of a band of kTileRows rows (render_bands.h hands them out).
//
// Every pixel is a pure function of the scene and its (column, row): no state carries
// from one pixel to the next that could change a value (the last-occluder memory in the
// scratch only reorders tests whose answer is a yes/no "any"). So the image is
// byte-identical whichever thread renders which rows.
template <typename Real>
class FlatSweep {
public:
    FlatSweep(const Scene& scene, PacketTracer<Real>&& tracer)
        : scene_(scene),
          tracer_(std::move(tracer)),
          spans_(tracer_.row_spans(scene)),
          background_row_(bytes_of_pixels(scene.columns)),
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

    // Rows [first_row, first_row + rows), rows <= kTileRows, into out[0..rows).
    void draw(int first_row, int rows, std::uint8_t* const* out, Workspace<Real>& work) const {
        Band band;
        band.first_row = first_row, band.end_row = first_row + rows, band.band_lo = scene_.columns;
        band.out = out;
        work.seen.clear();
        for (int r = band.first_row; r < band.end_row; ++r) eye_hits(r, band, work);
        shade(band, work);
    }

private:
    // A band of at most kTileRows rows: per row, its bytes, the columns some ellipsoid may
    // cover and its y; and those columns over the band.
    struct Band {
        std::uint8_t* const* out = nullptr;  // out[b]: row first_row + b
        int first_row = 0, end_row = 0;
        int lo[kTileRows] = {}, hi[kTileRows] = {};
        Real y[kTileRows] = {};
        int band_lo = 0, band_hi = -1;
    };

    // Row r as background, and the nearest hit of each of its eye rays that some
    // ellipsoid may meet (screen_bounds.h: a pixel that none may meet is the background,
    // without tracing), all columns of each ellipsoid's span at once (eye_rays.h).
    void eye_hits(int r, Band& band, Workspace<Real>& work) const {
        OwnLinesVector<Span>& in_row = work.in_row;
        std::copy(background_row_.begin(), background_row_.end(), band.out[r - band.first_row]);
        in_row.clear();
        int lo = scene_.columns, hi = -1;  // the columns some ellipsoid may cover
        // The row's y for the spans, in double: it decides only which columns are traced,
        // within the spans' margin of two columns (screen_bounds.h), never a pixel's value.
        const double span_y = pixel_y(scene_.top, scene_.bottom, r, scene_.rows);
        const std::vector<PixelRect>& rects = tracer_.screen_rects();
        for (std::uint32_t i = 0; i < rects.size(); ++i) {
            Span span{i, rects[i].first_column, rects[i].last_column};
            if (rects[i].first_row <= r && r <= rects[i].last_row &&
                spans_.narrow(i, span_y, span.first, span.last)) {
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
    void shade(const Band& band, Workspace<Real>& work) const {
        for (int c0 = band.band_lo; c0 <= band.band_hi; c0 += kTileColumns)
            for (int r = band.first_row; r < band.end_row; ++r) {
                const int b = r - band.first_row;
                const EyeRowHits<Real>& hits = work.hits[static_cast<std::size_t>(b)];
                std::uint8_t* const row_out = band.out[b];
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
                    PendingEyeHits<Real>& pending = work.pending[i];
                    pending.add(column_x_[column], band.y[b], near_z_, hits.t[column],
                                hits.inside[column] != 0, row_out + bytes_of_pixels(c));
                    if (pending.count == kPacket) pending.shade(tracer_, i, work.scratch);
                }
            }
        for (const std::uint32_t i : work.seen) work.pending[i].shade(tracer_, i, work.scratch);
    }

    const Scene& scene_;
    const PacketTracer<Real> tracer_;
    const RowSpans<typename PacketTracer<Real>::C> spans_;  // per ellipsoid, the columns of a row
    std::vector<std::uint8_t> background_row_;
    const std::vector<Real> column_x_;
    const EyeRays<Real> eye_rays_;
    Real near_z_;
};

}  // namespace

template <typename Real>
bool render_flat_sweep_to(const Scene& scene, RowSink& sink, unsigned threads) {
    if constexpr (kFlatSweepPrecision<Real>) {
        PacketTracer<Real> tracer(scene);
        if (!tracer.can_render()) return false;  // its tables freed before the tree is built
        const FlatSweep<Real> sweep(scene, std::move(tracer));
        // An image no eye ray can see an ellipsoid in is drawn alone: its rows are copies
        // of the background (testBehind at 400x400, whole process, interleaved, medians of
        // 300: 1.23 ms against 1.36 ms with the helper its pace called in).
        render_bands<kTileRows>(
            scene, sink, threads, [&] { return sweep.workspace(); },
            [&](int first_row, int rows, std::uint8_t* const* out, Workspace<Real>& work) {
                sweep.draw(first_row, rows, out, work);
            },
            sweep.sees_any() ? CallHelpers::WhenWorthIt : CallHelpers::Never);
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
