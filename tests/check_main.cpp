// Runs every TEST of the executable it is linked into and prints one summary line.
#include "check.h"

int main() {
    int failed_cases = 0;
    for (const check::Case& c : check::cases()) {
        const int before = check::failures();
        try {
            c.body();
        } catch (const std::exception& e) {
            check::fail(c.name, 0, std::string("unexpected exception: ") + e.what());
        }
        const bool ok = check::failures() == before;
        if (!ok) ++failed_cases;
        std::cout << (ok ? "ok    " : "FAIL  ") << c.name << "\n";
    }
    const int passed = static_cast<int>(check::cases().size()) - failed_cases;
    std::cout << passed << " passed, " << failed_cases << " failed\n";
    return failed_cases == 0 && passed > 0 ? 0 : 1;
}
