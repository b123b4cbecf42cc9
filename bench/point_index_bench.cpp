// Our kd-tree (photons/point_index.h) against nanoflann, side by side on the photons of BALL
// frame 0: build time, and the k-nearest queries photon mapping makes (k = 50 within 0.5 at
// every 4th photon: the irradiance precomputation; k = 300: the influence and L_t correction;
// k = 1: the irradiance-photon look-up of every final-gather ray). Checks that both find the
// same neighbours. Single thread, so the figures compare the trees, not the scheduler. Prints,
// asserts nothing. Run: build/point_index_bench
#include <tbb/global_control.h>
#include <nanoflann.hpp>

#include <cstdio>

#include "steadylight/base/stopwatch.h"
#include "steadylight/photons/photon_tracer.h"
#include "steadylight/shading/frame_context.h"

using namespace steadylight;

namespace {

struct PointCloud {
    const std::vector<Vec3>* points;
    size_t kdtree_get_point_count() const { return points->size(); }
    float kdtree_get_pt(size_t i, size_t dim) const { return (*points)[i][int(dim)]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const {
        return false;
    }
};
using NanoflannTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PointCloud>, PointCloud, 3, uint32_t>;

/// nanoflann's k nearest within the radius, as the renderer used it before its own tree.
void nanoflann_k_nearest(const NanoflannTree& tree, Vec3 p, int k, float max_distance2, std::vector<Neighbour>& out) {
    thread_local std::vector<uint32_t> indices;
    thread_local std::vector<float> distances2;
    indices.resize(size_t(k));
    distances2.resize(size_t(k));
    const float query[3] = {p.x, p.y, p.z};
    const size_t found = tree.knnSearch(query, size_t(k), indices.data(), distances2.data());
    out.clear();
    for (size_t i = 0; i < found; ++i)
        if (distances2[i] <= max_distance2) out.push_back({indices[i], distances2[i]});
}

}  // namespace

int main() {
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    const Scene scene(load_scene_desc(std::string(STEADYLIGHT_SOURCE_DIR) + "/scenes/ball.json"));
    const PreparedFrame ball(scene, 0);
    const TracedPhotons photons = trace_photons(ball.context(), PhotonSettings{});
    std::vector<Vec3> points;
    for (const Photon& photon : photons.global.photons()) points.push_back(photon.p);
    std::vector<Vec3> queries;
    for (size_t i = 0; i < points.size(); i += 4) queries.push_back(points[i]);
    std::printf("BALL frame 0: %zu global photons, %zu queries at every 4th photon, 1 thread\n\n", points.size(),
                queries.size());

    Stopwatch time;
    const PointIndex ours(points);
    const double ours_build = time.elapsed_s();
    time = Stopwatch();
    PointCloud cloud{&points};
    NanoflannTree theirs(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    const double theirs_build = time.elapsed_s();
    std::printf("%-28s %12s %12s %8s\n", "", "ours", "nanoflann", "ratio");
    std::printf("%-28s %10.1f ms %10.1f ms %7.2fx\n", "build", ours_build * 1e3, theirs_build * 1e3,
                theirs_build / ours_build);

    for (const int k : {1, 8, 50, 300}) {
        std::vector<Neighbour> found;
        long total = 0;
        time = Stopwatch();
        for (const Vec3& q : queries) ours.k_nearest(q, k, 0.25f, found), total += long(found.size());
        const double ours_s = time.elapsed_s();
        time = Stopwatch();
        for (const Vec3& q : queries) nanoflann_k_nearest(theirs, q, k, 0.25f, found);
        const double theirs_s = time.elapsed_s();
        // The same neighbours (as sets of distances: equal distances may come in either order).
        long mismatches = 0;
        std::vector<Neighbour> other;
        for (size_t i = 0; i < queries.size(); i += 97) {
            ours.k_nearest(queries[i], k, 0.25f, found);
            nanoflann_k_nearest(theirs, queries[i], k, 0.25f, other);
            mismatches +=
                found.size() != other.size() || (!found.empty() && found.back().distance2 != other.back().distance2);
        }
        const double n = double(queries.size());
        std::printf("k = %-3d within 0.5 (%5.1f found) %8.2f us %10.2f us %7.2fx  %s\n", k, double(total) / n,
                    ours_s / n * 1e6, theirs_s / n * 1e6, theirs_s / ours_s,
                    mismatches ? "RESULTS DIFFER" : "same results");
    }
    return 0;
}
