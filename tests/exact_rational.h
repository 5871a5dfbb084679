// Exact integers of any size and the exact values of decimal and binary numbers, for
// tests that decide a pixel in exact arithmetic (precision_thin_discs.cpp). Only what
// the exact hit test needs: sums, differences, products, signs; no division.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

namespace exact {

// A signed integer of any size: magnitude in base 2^32, least significant limb first,
// no leading zero limbs (zero has none).
struct Integer {
    bool negative = false;
    std::vector<std::uint32_t> limbs;
};

inline void trim(Integer& a) {
    while (!a.limbs.empty() && a.limbs.back() == 0) a.limbs.pop_back();
    if (a.limbs.empty()) a.negative = false;
}

inline Integer from_int(long long v) {
    Integer a;
    a.negative = v < 0;
    unsigned long long m =
        v < 0 ? 0ULL - static_cast<unsigned long long>(v) : static_cast<unsigned long long>(v);
    for (; m != 0; m >>= 32) a.limbs.push_back(static_cast<std::uint32_t>(m & 0xFFFFFFFFU));
    return a;
}

inline int sign(const Integer& a) { return a.limbs.empty() ? 0 : (a.negative ? -1 : 1); }

inline int compare_magnitude(const Integer& a, const Integer& b) {
    if (a.limbs.size() != b.limbs.size()) return a.limbs.size() < b.limbs.size() ? -1 : 1;
    for (std::size_t i = a.limbs.size(); i-- > 0;)
        if (a.limbs[i] != b.limbs[i]) return a.limbs[i] < b.limbs[i] ? -1 : 1;
    return 0;
}

// |a| + |b| and |a| - |b| (|a| >= |b|), signless.
inline std::vector<std::uint32_t> add_magnitudes(const Integer& a, const Integer& b) {
    std::vector<std::uint32_t> out(std::max(a.limbs.size(), b.limbs.size()) + 1, 0);
    std::uint64_t carry = 0;
    for (std::size_t i = 0; i + 1 < out.size(); ++i) {
        const std::uint64_t s =
            carry + (i < a.limbs.size() ? a.limbs[i] : 0U) + (i < b.limbs.size() ? b.limbs[i] : 0U);
        out[i] = static_cast<std::uint32_t>(s & 0xFFFFFFFFU);
        carry = s >> 32;
    }
    out.back() = static_cast<std::uint32_t>(carry);
    return out;
}

inline std::vector<std::uint32_t> subtract_magnitudes(const Integer& a, const Integer& b) {
    std::vector<std::uint32_t> out(a.limbs.size(), 0);
    std::int64_t borrow = 0;
    for (std::size_t i = 0; i < out.size(); ++i) {
        std::int64_t d =
            std::int64_t(a.limbs[i]) - (i < b.limbs.size() ? std::int64_t(b.limbs[i]) : 0) - borrow;
        borrow = d < 0 ? 1 : 0;
        if (d < 0) d += std::int64_t(1) << 32;
        out[i] = static_cast<std::uint32_t>(d);
    }
    return out;
}

inline Integer operator+(const Integer& a, const Integer& b) {
    Integer out;
    if (a.negative == b.negative) {
        out.limbs = add_magnitudes(a, b);
        out.negative = a.negative;
    } else if (compare_magnitude(a, b) >= 0) {
        out.limbs = subtract_magnitudes(a, b);
        out.negative = a.negative;
    } else {
        out.limbs = subtract_magnitudes(b, a);
        out.negative = b.negative;
    }
    trim(out);
    return out;
}

inline Integer operator-(Integer a) {
    a.negative = !a.negative;
    trim(a);
    return a;
}

inline Integer operator-(const Integer& a, const Integer& b) { return a + (-b); }

inline Integer operator*(const Integer& a, const Integer& b) {
    Integer out;
    if (a.limbs.empty() || b.limbs.empty()) return out;
    out.limbs.assign(a.limbs.size() + b.limbs.size(), 0);
    for (std::size_t i = 0; i < a.limbs.size(); ++i) {
        std::uint64_t carry = 0;
        for (std::size_t j = 0; j < b.limbs.size(); ++j) {
            const std::uint64_t t = std::uint64_t(a.limbs[i]) * b.limbs[j] + out.limbs[i + j] + carry;
            out.limbs[i + j] = static_cast<std::uint32_t>(t & 0xFFFFFFFFU);
            carry = t >> 32;
        }
        out.limbs[i + b.limbs.size()] = static_cast<std::uint32_t>(carry);
    }
    out.negative = a.negative != b.negative;
    trim(out);
    return out;
}

inline Integer power_of_ten(int n) {
    Integer out = from_int(1);
    const Integer ten = from_int(10);
    for (int i = 0; i < n; ++i) out = out * ten;
    return out;
}

inline Integer times_power_of_two(Integer a, int n) {
    const Integer two = from_int(2);
    for (int i = 0; i < n; ++i) a = a * two;
    return a;
}

// A decimal number as written in a scene: digits * 10^exponent, exactly.
struct Decimal {
    Integer digits;
    int exponent = 0;
};

inline Decimal parse_decimal(const std::string& text) {
    Decimal d;
    bool negative = false;
    std::size_t i = 0;
    if (i < text.size() && (text[i] == '-' || text[i] == '+')) negative = text[i++] == '-';
    const Integer ten = from_int(10);
    bool fraction = false;
    for (; i < text.size() && text[i] != 'e' && text[i] != 'E'; ++i) {
        if (text[i] == '.') {
            fraction = true;
            continue;
        }
        d.digits = d.digits * ten + from_int(text[i] - '0');
        if (fraction) --d.exponent;
    }
    if (i < text.size()) d.exponent += std::atoi(text.c_str() + i + 1);
    d.digits.negative = negative && sign(d.digits) != 0;
    return d;
}

// digits * 10^(exponent - unit): the decimal as a whole multiple of 10^unit
// (unit <= exponent).
inline Integer in_units_of_ten(const Decimal& d, int unit) {
    return d.digits * power_of_ten(d.exponent - unit);
}

// A finite double as mantissa * 2^exponent, exactly.
struct Binary {
    Integer mantissa;
    int exponent = 0;
};

inline Binary binary_of(double x) {
    Binary b;
    if (x == 0) return b;
    int e = 0;
    const double m = std::frexp(x, &e);  // x = m 2^e, 0.5 <= |m| < 1
    b.mantissa = from_int(static_cast<long long>(std::ldexp(m, 53)));
    b.exponent = e - 53;
    return b;
}

inline Integer in_units_of_two(const Binary& b, int unit) {
    return times_power_of_two(b.mantissa, b.exponent - unit);
}

}  // namespace exact
