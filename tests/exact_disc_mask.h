// The exact hit mask of one ellipsoid seen by the camera of SPEC section 3, computed in
// integers from the decimal scene: pixel (c, r) is a hit when the exact ray through its
// corner, x = LEFT + (RIGHT-LEFT) c/cols, y = TOP - (TOP-BOTTOM) r/rows, z = -NEAR, meets
// the exact ellipsoid (tangency included). A test of the line, not of where along it:
// for an ellipsoid wholly beyond the near plane meeting the line is seeing it
// (precision_thin_discs.cpp); elsewhere the caller checks where (ambiguous_outcomes.cpp).
//
// With o' = -C/s and d' = D/s, the line meets it when b^2 - a c >= 0 (a = d'.d',
// b = o'.d', c = o'.o' - 1). Times (s_x^2 s_y^2 s_z^2)^2, with K_i the product of the two
// other s_j^2 and G = sum C_i^2 K_i - s_x^2 s_y^2 s_z^2, that is the quadratic form
// D^T M D with M_ij = C_i K_i C_j K_j - [i = j] K_i G: integers once C and s are whole
// multiples of one power of ten, and homogeneous in D, so D may be scaled by any
// positive factor (to integers, from decimals or from doubles).
#pragma once

#include <array>
#include <string>

#include "exact_rational.h"

namespace exact {

class EllipsoidForm {
public:
    // centre and scale as written in the scene.
    EllipsoidForm(const std::array<std::string, 3>& centre, const std::array<std::string, 3>& scale) {
        std::array<Decimal, 3> c, s;
        int unit = 0;
        for (int i = 0; i < 3; ++i) {
            c[i] = parse_decimal(centre[i]), s[i] = parse_decimal(scale[i]);
            unit = std::min({unit, c[i].exponent, s[i].exponent});
        }
        std::array<Integer, 3> ci, s2;
        for (int i = 0; i < 3; ++i) {
            ci[i] = in_units_of_ten(c[i], unit);
            const Integer si = in_units_of_ten(s[i], unit);
            s2[i] = si * si;
        }
        const std::array<Integer, 3> k = {s2[1] * s2[2], s2[0] * s2[2], s2[0] * s2[1]};
        const Integer g =
            ci[0] * ci[0] * k[0] + ci[1] * ci[1] * k[1] + ci[2] * ci[2] * k[2] - s2[0] * s2[1] * s2[2];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                m_[i][j] = ci[i] * k[i] * ci[j] * k[j];
                if (i == j) m_[i][j] = m_[i][j] - k[i] * g;
            }
    }

    // Whether the line through the origin along d (integers, any common positive scale)
    // meets the ellipsoid.
    bool meets(const std::array<Integer, 3>& d) const { return side(d) >= 0; }
    // The sign of D^T M D: 1 where the line crosses the ellipsoid, 0 where it is exactly
    // tangent, -1 where it misses.
    int side(const std::array<Integer, 3>& d) const {
        Integer sum;
        for (int i = 0; i < 3; ++i) {
            sum = sum + m_[i][i] * (d[i] * d[i]);
            for (int j = i + 1; j < 3; ++j) sum = sum + m_[i][j] * (from_int(2) * d[i] * d[j]);
        }
        return sign(sum);
    }

private:
    Integer m_[3][3];
};

// The camera of a scene: the exact corner rays and the double ones the renderer casts.
class CornerRays {
public:
    CornerRays(const std::string& left, const std::string& right, const std::string& bottom,
               const std::string& top, const std::string& near, int columns, int rows)
        : columns_(columns), rows_(rows) {
        const Decimal l = parse_decimal(left), r = parse_decimal(right), b = parse_decimal(bottom),
                      t = parse_decimal(top), n = parse_decimal(near);
        const int unit = std::min({l.exponent, r.exponent, b.exponent, t.exponent, n.exponent, 0});
        left_ = in_units_of_ten(l, unit), right_ = in_units_of_ten(r, unit);
        bottom_ = in_units_of_ten(b, unit), top_ = in_units_of_ten(t, unit), near_ = in_units_of_ten(n, unit);
        left_d_ = std::stod(left), right_d_ = std::stod(right), bottom_d_ = std::stod(bottom);
        top_d_ = std::stod(top), near_d_ = std::stod(near);
    }

    // The exact ray through pixel (c, r)'s corner, times cols rows / 10^unit.
    std::array<Integer, 3> exact(int c, int r) const {
        const Integer x = left_ * from_int(columns_) + (right_ - left_) * from_int(c);  // x cols
        const Integer y = top_ * from_int(rows_) - (top_ - bottom_) * from_int(r);      // y rows
        return {x * from_int(rows_), y * from_int(columns_), -(near_ * from_int(columns_) * from_int(rows_))};
    }

    // The ray the renderer casts (render.cpp: the same double operations), exactly.
    std::array<Integer, 3> rounded(int c, int r) const {
        const double x = left_d_ + (right_d_ - left_d_) * static_cast<double>(c) / columns_;
        const double y = top_d_ - (top_d_ - bottom_d_) * static_cast<double>(r) / rows_;
        const std::array<Binary, 3> b = {binary_of(x), binary_of(y), binary_of(-near_d_)};
        int unit = 0;
        for (const Binary& v : b)
            if (sign(v.mantissa) != 0) unit = std::min(unit, v.exponent);
        return {in_units_of_two(b[0], unit), in_units_of_two(b[1], unit), in_units_of_two(b[2], unit)};
    }

private:
    int columns_, rows_;
    Integer left_, right_, bottom_, top_, near_;
    double left_d_, right_d_, bottom_d_, top_d_, near_d_;
};

}  // namespace exact
