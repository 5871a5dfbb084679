// A minimal test harness (the project uses the standard library only): TEST(name)
// defines a case, CHECK(...) records a failed expectation and carries on.
#pragma once

#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace check {

struct Case {
    const char* name;
    std::function<void()> body;
};

inline std::vector<Case>& cases() {
    static std::vector<Case> all;
    return all;
}

inline int& failures() {
    static int count = 0;
    return count;
}

struct Registrar {
    Registrar(const char* name, std::function<void()> body) { cases().push_back({name, std::move(body)}); }
};

inline void fail(const char* file, int line, const std::string& what) {
    ++failures();
    std::cerr << file << ":" << line << ": check failed: " << what << "\n";
}

}  // namespace check

#define CHECK_CAT2(a, b) a##b
#define CHECK_CAT(a, b) CHECK_CAT2(a, b)
#define TEST(name)                                                          \
    static void name();                                                     \
    static const check::Registrar CHECK_CAT(registrar_, name)(#name, name); \
    static void name()

#define CHECK(condition)                                               \
    do {                                                               \
        if (!(condition)) check::fail(__FILE__, __LINE__, #condition); \
    } while (0)

#define CHECK_EQ(actual, expected)                                                                         \
    do {                                                                                                   \
        const auto& check_a = (actual);                                                                    \
        const auto& check_e = (expected);                                                                  \
        if (!(check_a == check_e)) {                                                                       \
            std::ostringstream check_out;                                                                  \
            check_out << #actual << " == " << #expected << " (got " << check_a << ", expected " << check_e \
                      << ")";                                                                              \
            check::fail(__FILE__, __LINE__, check_out.str());                                              \
        }                                                                                                  \
    } while (0)

// Checks |actual - expected| <= tolerance.
#define CHECK_NEAR(actual, expected, tolerance)                                                           \
    do {                                                                                                  \
        const double check_a = static_cast<double>(actual);                                               \
        const double check_e = static_cast<double>(expected);                                             \
        if (!(check_a >= check_e - (tolerance) && check_a <= check_e + (tolerance))) {                    \
            std::ostringstream check_out;                                                                 \
            check_out.precision(17);                                                                      \
            check_out << #actual << " ~ " << #expected << " (got " << check_a << ", expected " << check_e \
                      << " +- " << (tolerance) << ")";                                                    \
            check::fail(__FILE__, __LINE__, check_out.str());                                             \
        }                                                                                                 \
    } while (0)
