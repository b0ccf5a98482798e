#include <BulletBuoyancy/graph/PermeabilityTexture.h>

#include <BulletBuoyancy/atlas/UvLayout.h>

// stb_image / stb_image_write (libstb-dev), compiled here with static linkage so another translation unit
// of the library (or of a user) may include its own copy without clashing symbols.
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_HDR
#define STBI_NO_LINEAR
// Only the formats users paint damage maps in. stb's PNM reader overflows a signed int on huge header
// numbers (found by fuzz/fuzz_permeability_image, UBSan in stbi__pnm_getinteger); PSD, PIC and GIF are
// left out with it: such a file is "not an image" (docs/bad-input.md).
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_ONLY_BMP
#define STBI_ONLY_TGA
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wunused-but-set-variable"
#endif
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>

namespace buoyancy {

namespace {

/// Wrap an integer texel index into [0, n).
/// The PNG `data` without its zero-length IDAT chunks (they hold no image data; dropping them does not change the
/// image), or an empty vector when there are none. The scan stops at IEND or at the first chunk that runs past the
/// end of the data (what follows is kept as it is: stb_image reports it).
/// stb_image 2.27 copies a first, empty IDAT chunk from a null buffer (memcpy(nullptr, …, 0): undefined behaviour
/// that UBSan reports; found by fuzz_permeability_image).
std::vector<unsigned char> withoutEmptyIdat(const unsigned char* data, std::size_t size) {
    auto be32 = [&](std::size_t o) {
        return (std::uint32_t(data[o]) << 24) | (std::uint32_t(data[o + 1]) << 16) | (std::uint32_t(data[o + 2]) << 8) |
               std::uint32_t(data[o + 3]);
    };
    std::vector<std::size_t> drop;  // offsets of the empty IDAT chunks (12 bytes each: length, type, CRC)
    std::size_t at = 8;             // after the signature
    while (at + 12 <= size) {
        const std::size_t length = be32(at);
        if (length > size - at - 12) break;  // malformed from here on: left to stb_image
        if (length == 0 && std::equal(data + at + 4, data + at + 8, "IDAT")) drop.push_back(at);
        if (std::equal(data + at + 4, data + at + 8, "IEND")) break;
        at += 12 + length;
    }
    if (drop.empty()) return {};
    std::vector<unsigned char> out;
    out.reserve(size - 12 * drop.size());
    std::size_t from = 0;
    for (std::size_t d : drop) {
        out.insert(out.end(), data + from, data + d);
        from = d + 12;
    }
    out.insert(out.end(), data + from, data + size);
    return out;
}

int wrapIndex(long long i, int n) {
    long long r = i % n;
    if (r < 0) r += n;
    return int(r);
}

/// Closest point of triangle (a, b, c) to p as barycentric weights (Ericson, Real-Time Collision Detection 5.1.5).
Eigen::Vector3d closestBarycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                   const Eigen::Vector3d& c) {
    const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        const double v = d1 / (d1 - d3);
        return {1 - v, v, 0};
    }
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        const double w = d2 / (d2 - d6);
        return {1 - w, 0, w};
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return {0, 1 - w, w};
    }
    const double denom = va + vb + vc;
    if (!(std::abs(denom) > 0)) return {1.0 / 3, 1.0 / 3, 1.0 / 3};  // degenerate triangle
    const double v = vb / denom, w = vc / denom;
    return {1 - v - w, v, w};
}

}  // namespace

double PermeabilityImage::sample(double u, double v, TextureFilter filter) const {
    if (width <= 0 || height <= 0 || !std::isfinite(u) || !std::isfinite(v)) return 0.0;
    // Texel coordinates: x grows with u from the left edge, y from the top row (v = 1) down.
    const double x = u * width, y = (1.0 - v) * height;
    if (!(std::abs(x) < 1e15 && std::abs(y) < 1e15)) return 0.0;
    if (filter == TextureFilter::Nearest) {
        const int i = wrapIndex((long long)std::floor(x), width), j = wrapIndex((long long)std::floor(y), height);
        return value[std::size_t(j) * std::size_t(width) + std::size_t(i)];
    }
    // Bilinear between texel centres (x − 0.5, y − 0.5).
    const double fx = x - 0.5, fy = y - 0.5;
    const double x0 = std::floor(fx), y0 = std::floor(fy);
    const double tx = fx - x0, ty = fy - y0;
    const int i0 = wrapIndex((long long)x0, width), i1 = wrapIndex((long long)x0 + 1, width);
    const int j0 = wrapIndex((long long)y0, height), j1 = wrapIndex((long long)y0 + 1, height);
    auto at = [&](int i, int j) { return double(value[std::size_t(j) * std::size_t(width) + std::size_t(i)]); };
    return (1 - ty) * ((1 - tx) * at(i0, j0) + tx * at(i1, j0)) + ty * ((1 - tx) * at(i0, j1) + tx * at(i1, j1));
}

PermeabilityImage decodePermeabilityImage(const unsigned char* data, std::size_t size, const std::string& name) {
    if (size == 0 || !data) throw std::invalid_argument(name + ": the file is empty (0 bytes)");
    if (size > std::size_t(2147483647)) throw std::invalid_argument(name + ": the file is larger than 2 GiB");
    // A PNG header's own size (stb reports a 0 × N PNG only as an unknown type once every decoder failed).
    static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    if (size >= 24 && std::equal(kPng, kPng + 8, data) && std::equal(data + 12, data + 16, "IHDR")) {
        auto be32 = [&](std::size_t o) {
            return (std::uint32_t(data[o]) << 24) | (std::uint32_t(data[o + 1]) << 16) | (std::uint32_t(data[o + 2]) << 8) |
                   std::uint32_t(data[o + 3]);
        };
        if (be32(16) == 0 || be32(20) == 0)
            throw std::invalid_argument(name + ": the image has zero size (" + std::to_string(be32(16)) + "x" +
                                        std::to_string(be32(20)) + " texels)");
    }
    std::vector<unsigned char> normalised;  // a PNG without empty IDAT chunks (withoutEmptyIdat), when it had some
    if (size >= 8 && std::equal(kPng, kPng + 8, data)) {
        normalised = withoutEmptyIdat(data, size);
        if (!normalised.empty()) {
            data = normalised.data();
            size = normalised.size();
        }
    }
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(data, int(size), &w, &h, &comp)) {
        const char* why = stbi_failure_reason();
        if (why && std::string(why) == "0-pixel image")
            throw std::invalid_argument(name + ": the image has zero size (0 texels wide or high)");
        throw std::invalid_argument(name + ": not an image stb_image can read (" + (why ? why : "unknown format") +
                                    "); expected PNG, JPEG, BMP or TGA");
    }
    if (w <= 0 || h <= 0)
        throw std::invalid_argument(name + ": the image has zero size (" + std::to_string(w) + "x" + std::to_string(h) + ")");
    if (w > kMaxPermeabilityImageSide || h > kMaxPermeabilityImageSide)
        throw std::invalid_argument(name + ": " + std::to_string(w) + "x" + std::to_string(h) +
                                    " texels, larger than " + std::to_string(kMaxPermeabilityImageSide) + " per side");
    if (comp != 3 && comp != 4)
        throw std::invalid_argument(name + ": " + std::to_string(comp) + (comp == 1 ? " channel (grey)" : " channels") +
                                    "; a permeability texture needs RGB or RGBA (its red channel is the open-area fraction)");
    std::unique_ptr<unsigned char, void (*)(void*)> pixels(stbi_load_from_memory(data, int(size), &w, &h, &comp, 3),
                                                           &stbi_image_free);
    if (!pixels) {
        const char* why = stbi_failure_reason();
        throw std::invalid_argument(name + ": not an image stb_image can read (" + (why ? why : "decoding failed") + ")");
    }
    if (w <= 0 || h <= 0)
        throw std::invalid_argument(name + ": the image has zero size (" + std::to_string(w) + "x" + std::to_string(h) + ")");
    PermeabilityImage img;
    img.width = w;
    img.height = h;
    img.value.resize(std::size_t(w) * std::size_t(h));
    for (std::size_t i = 0; i < img.value.size(); ++i) img.value[i] = float(pixels.get()[3 * i]) / 255.0f;
    return img;
}

PermeabilityImage loadPermeabilityImage(const std::string& path) {
    std::error_code ec;  // a directory opens as a stream but throws std::ios_base::failure on the first read
    if (!std::filesystem::is_regular_file(path, ec)) throw std::invalid_argument(path + ": cannot read the file (not a file)");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::invalid_argument(path + ": cannot read the file");
    const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw std::invalid_argument(path + ": cannot read the file");
    return decodePermeabilityImage(bytes.data(), bytes.size(), path);
}

PermeabilityUvs permeabilityUvs(const TriangleMesh& mesh, int atlasSize) {
    PermeabilityUvs out;
    bool finite = mesh.hasUvs();
    if (finite)
        for (const Eigen::Vector2d& t : mesh.corner_uvs)
            if (!t.allFinite()) {
                finite = false;
                break;
            }
    if (finite) {
        out.corner_uvs = mesh.corner_uvs;
        return out;
    }
    out.corner_uvs = generateAtlas(mesh, atlasSize);
    out.generated = true;
    return out;
}

std::vector<Eigen::Vector2d> surfaceSampleUvs(const SurfaceSamples& samples, const TriangleMesh& mesh,
                                              const std::vector<Eigen::Vector2d>& cornerUvs) {
    if (cornerUvs.size() != 3 * mesh.triangleCount())
        throw std::invalid_argument("UVs: " + std::to_string(cornerUvs.size()) + " corner UVs for " +
                                    std::to_string(mesh.triangleCount()) + " triangles (need 3 per triangle)");
    std::vector<Eigen::Vector2d> uvs(samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const std::size_t t = i < samples.triangle.size() ? samples.triangle[i] : mesh.triangleCount();
        if (t >= mesh.triangleCount())
            throw std::invalid_argument("samples: sample " + std::to_string(i) + " has no valid triangle index");
        const Eigen::Vector3d bary =
            closestBarycentric(Eigen::Vector3d(samples.px[i], samples.py[i], samples.pz[i]), mesh.corner(t, 0),
                               mesh.corner(t, 1), mesh.corner(t, 2));
        uvs[i] = bary[0] * cornerUvs[3 * t] + bary[1] * cornerUvs[3 * t + 1] + bary[2] * cornerUvs[3 * t + 2];
    }
    return uvs;
}

std::vector<double> permeabilityFromImage(const std::vector<Eigen::Vector2d>& sampleUvs, const PermeabilityImage& image,
                                          TextureFilter filter) {
    std::vector<double> v(sampleUvs.size());
    for (std::size_t i = 0; i < v.size(); ++i)
        v[i] = std::clamp(image.sample(sampleUvs[i].x(), sampleUvs[i].y(), filter), 0.0, 1.0);
    return v;
}

void writeAtlasObj(const TriangleMesh& mesh, const std::vector<Eigen::Vector2d>& cornerUvs, const std::string& path) {
    if (cornerUvs.size() != 3 * mesh.triangleCount())
        throw std::runtime_error("atlas: " + std::to_string(cornerUvs.size()) + " corner UVs for " +
                                 std::to_string(mesh.triangleCount()) + " triangles");
    std::ofstream out(path);
    if (!out) throw std::runtime_error(path + ": cannot write");
    out.precision(17);
    out << "# BulletBuoyancy permeability atlas: paint the texture in these UVs (image top row = v 1)\n";
    for (const Eigen::Vector3d& v : mesh.vertices) out << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
    for (const Eigen::Vector2d& t : cornerUvs) out << "vt " << t.x() << ' ' << t.y() << '\n';
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        out << 'f';
        for (int k = 0; k < 3; ++k) out << ' ' << mesh.triangles[t][k] + 1 << '/' << 3 * t + std::size_t(k) + 1;
        out << '\n';
    }
    if (!out) throw std::runtime_error(path + ": error while writing");
}

void writeAtlasTemplatePng(const std::vector<Eigen::Vector2d>& cornerUvs, int size, const std::string& path) {
    if (size < 1 || size > kMaxPermeabilityImageSide) throw std::runtime_error("atlas template: bad size " + std::to_string(size));
    std::vector<unsigned char> rgb(std::size_t(size) * std::size_t(size) * 3, 0);
    // Mark each texel whose centre lies in a UV triangle (scanning each triangle's bounding box).
    for (std::size_t t = 0; t + 2 < cornerUvs.size(); t += 3) {
        Eigen::Vector2d p[3];
        for (int k = 0; k < 3; ++k) p[k] = Eigen::Vector2d(cornerUvs[t + k].x() * size, (1.0 - cornerUvs[t + k].y()) * size);
        if (!p[0].allFinite() || !p[1].allFinite() || !p[2].allFinite()) continue;
        const double area = (p[1] - p[0]).x() * (p[2] - p[0]).y() - (p[1] - p[0]).y() * (p[2] - p[0]).x();
        if (area == 0) continue;
        const int x0 = std::max(0, int(std::floor(std::min({p[0].x(), p[1].x(), p[2].x()}))));
        const int x1 = std::min(size - 1, int(std::ceil(std::max({p[0].x(), p[1].x(), p[2].x()}))));
        const int y0 = std::max(0, int(std::floor(std::min({p[0].y(), p[1].y(), p[2].y()}))));
        const int y1 = std::min(size - 1, int(std::ceil(std::max({p[0].y(), p[1].y(), p[2].y()}))));
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                const Eigen::Vector2d c(x + 0.5, y + 0.5);
                bool inside = true;
                for (int k = 0; k < 3 && inside; ++k) {
                    const Eigen::Vector2d e = p[(k + 1) % 3] - p[k], q = c - p[k];
                    inside = (e.x() * q.y() - e.y() * q.x()) * area >= 0;
                }
                if (inside) rgb[(std::size_t(y) * std::size_t(size) + std::size_t(x)) * 3 + 1] = 96;
            }
    }
    if (!stbi_write_png(path.c_str(), size, size, 3, rgb.data(), size * 3))
        throw std::runtime_error(path + ": cannot write the PNG");
}

}  // namespace buoyancy
