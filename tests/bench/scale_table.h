// The benchmark's tables for scenes far beyond the course's size (issue 14):
//   (d) sphereflakes of levels 3-5 and 1k, 10k and 100k random ellipsoids at 400x400,
//       whole process on all cores: wall time, Mrays/s and, where POV-Ray is on the
//       machine, its time on the same scene (2 threads) and the ratio; Embree 3's time (a
//       renderer on it, measured in this run where given, else issue 14's figure); the growth
//       t(random 100k) / t(random 1k);
//   (e) random 100k read and prepared (RES 1 1): time and peak memory; rendered on 64
//       threads: peak memory; and 2,000 random discs 1e-9 and 1e-11 thick: time.
// Run in the benchmark's scratch folder (the working directory).
#pragma once

#include <filesystem>

// make_scene: tests/bench/make_scene.cpp's program. povray: ../shared/tools/povray/render.sh,
// or empty; used only where `povray` runs. embree: tests/bench/embree_tracer.cpp's program, or
// empty; where it runs, (d) times it as raytracer.exe (same runs, alternating, whole process)
// in place of issue 14's figures.
void scale_table(const std::filesystem::path& raytracer, const std::filesystem::path& make_scene,
                 const std::filesystem::path& povray, const std::filesystem::path& embree, bool quick,
                 bool& failed);
