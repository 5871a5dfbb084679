// Grades one scene: renders it with the program under test in an empty scratch folder,
// finds and reads the image it wrote, and judges it against the key. Every way the run
// can go wrong ends in a sentence for the student (SceneResult::problem).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "options.h"
#include "pass_rule.h"
#include "raytracer/image.h"

namespace grade {

struct SceneResult {
    std::string name;                 // "testShadow"
    std::string key_name;             // "keyShadow"
    std::string problem;              // why there is no image to compare; empty when compared
    std::vector<std::string> notes;   // facts that do not fail the scene (slow render)
    bool ungradable = false;          // not the program's doing: the scene or its key cannot be
                                      // read, or the run's folder made (scratch_unwritable)
    bool interrupted = false;         // the grader itself was interrupted meanwhile
    bool scratch_unwritable = false;  // the grader could not make the run's folder (exit 3)
    double seconds = 0;               // the render's wall time
    Judgement judgement;
    rt::Image key, got;  // kept for the difference picture
    bool passed() const { return problem.empty() && judgement.passed(); }
};

// The key of testName.txt is keyName.ppm (the course's naming); of other.txt, other.ppm.
std::filesystem::path key_for(const std::filesystem::path& keys, const std::filesystem::path& scene);

// Removes the folder and all in it, write-protected folders in it too, trying again for
// half a second when a file is locked; false when it could not.
bool remove_folder(const std::filesystem::path& folder);

// scratch is a folder of the grader's own: it is emptied and used for this scene.
SceneResult grade_scene(const std::filesystem::path& scene, const Options& options,
                        const std::filesystem::path& scratch);

}  // namespace grade
