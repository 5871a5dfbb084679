// path_gap: how far the tree (render_tree_to()) is from the path render_to() takes,
// scene by scene, rendering alone in this process (no reading, no writing): the figure
// that says when the flat sweep can go (docs/speed.md, "What is next"). For each scene
// the two paths run alternately, `runs` times each, and the medians are printed with
// their ratio; the images are compared too (they must be the same bytes).
//
// usage: path_gap [--runs N] [--threads N] SCENE...
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "raytracer/parser.h"
#include "raytracer/render.h"
#include "raytracer/render_tree.h"
#include "raytracer/row_sink.h"
#include "raytracer/scene_error.h"

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    int runs = 11;
    unsigned threads = 1;
    std::vector<std::string> scenes;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--runs" && i + 1 < argc)
            runs = std::max(1, std::atoi(argv[++i]));
        else if (a == "--threads" && i + 1 < argc)
            threads = static_cast<unsigned>(std::max(1, std::atoi(argv[++i])));
        else
            scenes.push_back(a);
    }
    if (scenes.empty()) {
        std::fprintf(stderr, "usage: path_gap [--runs N] [--threads N] SCENE...\n");
        return 2;
    }
    std::printf("rendering alone on %u thread(s), medians of %d, ms: the path taken, the tree, their ratio\n",
                threads, runs);
    bool differ = false;
    for (const std::string& file : scenes) {
        rt::Scene scene;
        try {
            scene = rt::load_scene(file);
        } catch (const rt::SceneError& e) {
            std::fprintf(stderr, "%s\n", e.what());
            return 1;
        }
        std::vector<double> taken, tree;
        rt::ImageSink taken_image(scene.columns, scene.rows), tree_image(scene.columns, scene.rows);
        for (int r = 0; r < runs; ++r) {
            for (const bool through_tree : {false, true}) {
                rt::ImageSink sink(scene.columns, scene.rows);  // its room made before the clock starts
                const auto start = std::chrono::steady_clock::now();
                if (through_tree)
                    rt::render_tree_to<double>(scene, sink, threads);
                else
                    rt::render_to<double>(scene, sink, threads);
                const double ms =
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                        .count();
                (through_tree ? tree : taken).push_back(ms);
                (through_tree ? tree_image : taken_image) = std::move(sink);
            }
        }
        const bool same = taken_image.image.rgb == tree_image.image.rgb;
        differ = differ || !same;
        const std::string name = file.substr(file.find_last_of("/\\") + 1);
        std::printf("  %-24s %9.2f %9.2f  x%.2f%s\n", name.c_str(), median(taken), median(tree),
                    median(tree) / median(taken), same ? "" : "  IMAGES DIFFER");
    }
    return differ ? 1 : 0;
}
