// baseline_tracer <scene-file>: the simplest correct tracer of the same spec (SPEC.md),
// kept only as the yardstick of the benchmark (issue 5, target b). One thread, double,
// no culling, no precomputation, no tricks: every ray is tested against every
// ellipsoid, every shadow ray against all of them. It reads only valid scenes.
// Its images equal raytracer.exe's but for a few tangent or rim pixels (it uses the
// textbook discriminant b^2 - a c, not the cancellation-free form of ellipsoid.h).
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace {

struct V {
    double x = 0, y = 0, z = 0;
};
V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V operator*(V a, double k) { return {a.x * k, a.y * k, a.z * k}; }
V operator*(V a, V b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
V operator/(V a, V b) { return {a.x / b.x, a.y / b.y, a.z / b.z}; }
double dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V normalize(V a) { return a * (1 / std::sqrt(dot(a, a))); }

struct Sphere {
    V centre, scale, colour;
    double ka, kd, ks, kr, n;
};
struct Light {
    V position, intensity;
};
struct Scene {
    double near_plane = 0, left = 0, right = 0, bottom = 0, top = 0;
    int columns = 0, rows = 0;
    std::vector<Sphere> spheres;
    std::vector<Light> lights;
    V back, ambient;
    std::string output;
};

V read_v(std::istream& in) {
    V v;
    in >> v.x >> v.y >> v.z;
    return v;
}

Scene read_scene(const char* file) {
    std::ifstream in(file);
    Scene s;
    std::string key;
    while (in >> key) {
        if (key == "NEAR") in >> s.near_plane;
        if (key == "LEFT") in >> s.left;
        if (key == "RIGHT") in >> s.right;
        if (key == "BOTTOM") in >> s.bottom;
        if (key == "TOP") in >> s.top;
        if (key == "RES") in >> s.columns >> s.rows;
        if (key == "BACK") s.back = read_v(in);
        if (key == "AMBIENT") s.ambient = read_v(in);
        if (key == "OUTPUT") in >> s.output;
        if (key == "SPHERE") {
            Sphere p;
            in >> key;
            p.centre = read_v(in), p.scale = read_v(in), p.colour = read_v(in);
            in >> p.ka >> p.kd >> p.ks >> p.kr >> p.n;
            s.spheres.push_back(p);
        }
        if (key == "LIGHT") {
            Light l;
            in >> key;
            l.position = read_v(in), l.intensity = read_v(in);
            s.lights.push_back(l);
        }
    }
    return s;
}

// Both roots of the ray against the unit sphere after mapping it into the sphere's
// space; false when it misses. A tangent ray (discriminant a few ulps below 0) hits.
bool intersect(const Sphere& s, V origin, V direction, double& t1, double& t2) {
    const V o = (origin - s.centre) / s.scale, d = direction / s.scale;
    const double a = dot(d, d), b = dot(o, d), c = dot(o, o) - 1;
    double disc = b * b - a * c;
    if (disc < -1e-12 * b * b) return false;
    if (disc < 0) disc = 0;
    t1 = (-b - std::sqrt(disc)) / a;
    t2 = (-b + std::sqrt(disc)) / a;
    return true;
}

V trace(const Scene& s, V origin, V direction, double min_t, int depth, V miss) {
    min_t *= 1 + 8 * 2.220446049250313e-16;  // a root at min_t is not visible (SPEC 7)
    const Sphere* hit = nullptr;
    double best = 0;
    bool inside = false;
    for (const Sphere& sp : s.spheres) {
        double t1, t2;
        if (!intersect(sp, origin, direction, t1, t2)) continue;
        const double t = t1 > min_t ? t1 : t2;
        if (t > min_t && (hit == nullptr || t < best)) hit = &sp, best = t, inside = !(t1 > min_t);
    }
    if (hit == nullptr) return miss;

    const V p = origin + direction * best;
    V normal = normalize((p - hit->centre) / (hit->scale * hit->scale));
    if (inside) normal = normal * -1;
    const V view = normalize(direction * -1);
    V colour = (s.ambient * hit->ka) * hit->colour;
    for (const Light& light : s.lights) {
        const V to_light = light.position - p;
        bool blocked = false;
        for (const Sphere& sp : s.spheres) {
            double t1, t2;
            if (intersect(sp, p, to_light, t1, t2) && ((t1 > 0.001 && t1 < 1) || (t2 > 0.001 && t2 < 1)))
                blocked = true;
        }
        if (blocked) continue;
        const V l = normalize(to_light);
        const double nl = dot(normal, l);
        if (!(nl > 0)) continue;
        colour = colour + ((light.intensity * hit->kd) * nl) * hit->colour;
        const double rv = dot(normal * (2 * nl) - l, view);
        if (rv > 0) colour = colour + (light.intensity * hit->ks) * std::pow(rv, hit->n);
    }
    if (hit->kr > 0 && depth > 0) {
        const V mirrored = direction - normal * (2 * dot(normal, direction));
        colour = colour + trace(s, p, mirrored, 0.0001, depth - 1, V{}) * hit->kr;
    }
    return colour;
}

unsigned char to_byte(double c) { return c >= 1 ? 255 : c > 0 ? static_cast<unsigned char>(c * 255) : 0; }

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: baseline_tracer <scene-file>\n");
        return 2;
    }
    const Scene s = read_scene(argv[1]);
    std::vector<unsigned char> rgb;
    for (int r = 0; r < s.rows; ++r)
        for (int c = 0; c < s.columns; ++c) {
            const double x = s.left + (s.right - s.left) * c / s.columns;
            const double y = s.top - (s.top - s.bottom) * r / s.rows;
            const V colour = trace(s, V{}, V{x, y, -s.near_plane}, 1, 3, s.back);
            rgb.push_back(to_byte(colour.x)), rgb.push_back(to_byte(colour.y)),
                rgb.push_back(to_byte(colour.z));
        }
    std::ofstream out(s.output, std::ios::binary);
    out << "P6\n" << s.columns << ' ' << s.rows << "\n255\n";
    out.write(reinterpret_cast<const char*>(rgb.data()), static_cast<std::streamsize>(rgb.size()));
    return out ? 0 : 1;
}
