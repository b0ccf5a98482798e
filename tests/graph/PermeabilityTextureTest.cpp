// Permeability textures: the red channel / 255 of an image in the model's UVs (or the generated
// atlas) is each surface sample's open-area fraction; bad images fail with the key and file named; the
// per-sample map can be changed at run time all-or-nothing. Oracles: the primitive box's documented UV
// layout (a 3 × 2 grid of face charts) gives each face's open area exactly; images are written here.
#include <catch2/catch.hpp>

#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include "scene/SceneErrors.h"
#include "cli/RunCommand.h"
#include "scene/SceneFile.h"
#include <BulletBuoyancy/graph/PermeabilityMap.h>
#include <BulletBuoyancy/graph/PermeabilityTexture.h>
#include <BulletBuoyancy/bullet/btFloodingAction.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#endif
#include <stb/stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <vector>
#include <unistd.h>  // getpid: a private temporary folder per test process

using namespace buoyancy;

namespace {

namespace fs = std::filesystem;

fs::path tempDir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("buoyancy_perm_" + std::to_string(::getpid()) + "_" + name);
    fs::create_directories(d);
    return d;
}

/// Write an RGB(A) or grey PNG of w × h texels from a per-texel function (row 0 = top).
template <class F>
void writePng(const fs::path& path, int w, int h, int channels, F texel) {
    std::vector<unsigned char> px(std::size_t(w) * h * channels);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c) px[(std::size_t(y) * w + x) * channels + c] = texel(x, y, c);
    REQUIRE(stbi_write_png(path.string().c_str(), w, h, channels, px.data(), w * channels) != 0);
}

/// Face of the primitive box a sample lies on, from its area vector: 0 −x, 1 +x, 2 −y, 3 +y, 4 −z, 5 +z
/// (PrimitiveMeshes.cpp: face f = 2·axis + side sits in UV cell (f mod 3, f div 3) of a 3 × 2 grid).
int boxFace(const SurfaceSamples& s, std::size_t i) {
    const Eigen::Vector3d a(s.ax[i], s.ay[i], s.az[i]);
    int axis = 0;
    a.cwiseAbs().maxCoeff(&axis);
    return 2 * axis + (a[axis] > 0 ? 1 : 0);
}

/// Image texel block (column, row from the top) of face f in the 3 × 2 grid: column f mod 3, v cell f div 3
/// counted from the bottom (v = 0), so the image row is 1 − f div 3.
void faceBlock(int f, int& column, int& row) {
    column = f % 3;
    row = 1 - f / 3;
}

std::string errorOf(const std::function<void()>& fn) {
    try {
        fn();
    } catch (const std::exception& e) {
        return e.what();
    }
    return "no error";
}

}  // namespace

TEST_CASE("permeability image: red / 255, top row is v = 1, nearest and bilinear, wrapping", "[graph]") {
    const fs::path dir = tempDir("lookup");
    // 3 × 2 texels: red values 0, 51, 102 (top row), 153, 204, 255 (bottom row); green/blue noise.
    writePng(dir / "img.png", 3, 2, 3, [](int x, int y, int c) { return c == 0 ? 51 * (3 * y + x) : 200 - 70 * c; });
    const PermeabilityImage img = loadPermeabilityImage((dir / "img.png").string());
    REQUIRE(img.width == 3);
    REQUIRE(img.height == 2);
    // Texel centres: u = (x + 0.5)/3, v = 1 − (y + 0.5)/2.
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) {
            const double expect = 51.0 * (3 * y + x) / 255.0;
            const double u = (x + 0.5) / 3, v = 1 - (y + 0.5) / 2;
            CHECK(img.sample(u, v, TextureFilter::Nearest) == Approx(expect).margin(1e-6));
            CHECK(img.sample(u, v, TextureFilter::Bilinear) == Approx(expect).margin(1e-6));
            CHECK(img.sample(u + 2, v - 3, TextureFilter::Nearest) == Approx(expect).margin(1e-6));  // wraps
        }
    // Bilinear halfway between the centres of texels (0, 0) and (1, 0): the mean.
    CHECK(img.sample(1.0 / 3, 0.75) == Approx((0 + 51) / 2.0 / 255).margin(1e-6));
    // Halfway between all four of the top-left block: mean of 0, 51, 153, 204.
    CHECK(img.sample(1.0 / 3, 0.5) == Approx((0 + 51 + 153 + 204) / 4.0 / 255).margin(1e-6));
    CHECK(img.sample(std::nan(""), 0.5) == 0.0);
    // RGBA works too (alpha ignored).
    writePng(dir / "rgba.png", 2, 2, 4, [](int, int, int c) { return c == 0 ? 255 : c == 3 ? 7 : 0; });
    CHECK(loadPermeabilityImage((dir / "rgba.png").string()).value[3] == Approx(1.0));
    fs::remove_all(dir);
}

TEST_CASE("permeability image errors name the file: missing, empty, not an image, zero size, channels", "[graph]") {
    const fs::path dir = tempDir("errors");
    const std::string missing = (dir / "nothere.png").string();
    CHECK_THAT(errorOf([&] { loadPermeabilityImage(missing); }), Catch::Contains(missing) && Catch::Contains("cannot read"));
    CHECK_THAT(errorOf([&] { loadPermeabilityImage(dir.string()); }), Catch::Contains("cannot read") && Catch::Contains("not a file"));
    { std::ofstream(dir / "empty.png"); }
    CHECK_THAT(errorOf([&] { loadPermeabilityImage((dir / "empty.png").string()); }),
               Catch::Contains("empty.png") && Catch::Contains("empty"));
    { std::ofstream(dir / "text.png") << "this is not an image\n"; }
    CHECK_THAT(errorOf([&] { loadPermeabilityImage((dir / "text.png").string()); }),
               Catch::Contains("text.png") && Catch::Contains("not an image"));
    // Fuzz regression (fuzz_permeability_image): a PNM header with a number that overflows stb's int parser
    // (UB inside stb's PNM reader). PNM is not a permeability format: a clear "not an image", no UB.
    { std::ofstream(dir / "huge.ppm", std::ios::binary) << "P6\n4666666666666 2\n255\n"; }
    CHECK_THAT(errorOf([&] { loadPermeabilityImage((dir / "huge.ppm").string()); }),
               Catch::Contains("huge.ppm") && Catch::Contains("not an image"));
    // A PNG whose header says 0 × 1 texels (signature, IHDR; stb does not check CRCs).
    {
        const unsigned char png[] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A, 0, 0, 0, 13, 'I', 'H', 'D', 'R',
                                     0, 0, 0, 0, 0, 0, 0, 1, 8, 2, 0, 0, 0, 0, 0, 0, 0,
                                     0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
        std::ofstream(dir / "zero.png", std::ios::binary).write(reinterpret_cast<const char*>(png), sizeof png);
    }
    CHECK_THAT(errorOf([&] { loadPermeabilityImage((dir / "zero.png").string()); }),
               Catch::Contains("zero.png") && Catch::Contains("zero size"));
    writePng(dir / "grey.png", 4, 4, 1, [](int, int, int) { return 255; });
    CHECK_THAT(errorOf([&] { loadPermeabilityImage((dir / "grey.png").string()); }),
               Catch::Contains("grey.png") && Catch::Contains("1 channel") && Catch::Contains("RGB"));
    writePng(dir / "ga.png", 4, 4, 2, [](int, int, int) { return 255; });
    CHECK_THAT(errorOf([&] { loadPermeabilityImage((dir / "ga.png").string()); }),
               Catch::Contains("ga.png") && Catch::Contains("2 channels"));
    fs::remove_all(dir);
}

TEST_CASE("texture in the model's UVs opens exactly the painted faces of a box", "[graph]") {
    const fs::path dir = tempDir("box");
    // 30 × 20 image in 10 × 10 blocks, one per face chart: +y (face 3) fully open, +x (face 1) red 51 (0.2).
    auto red = [](int f) { return f == 3 ? 255 : f == 1 ? 51 : 0; };
    writePng(dir / "faces.png", 30, 20, 3, [&](int x, int y, int c) {
        if (c != 0) return 0;
        for (int f = 0; f < 6; ++f) {
            int col, row;
            faceBlock(f, col, row);
            if (x / 10 == col && y / 10 == row) return red(f);
        }
        return 0;
    });
    const PermeabilityImage img = loadPermeabilityImage((dir / "faces.png").string());
    const TriangleMesh mesh = makeBoxMesh(2.0, 1.0, 3.0);
    REQUIRE(mesh.hasUvs());
    auto shape = btBuoyancyShape::create(mesh);
    const SurfaceSamples& s = shape->getDragSamples();
    const PermeabilityUvs uvs = permeabilityUvs(shape->getMesh(), img.width);
    CHECK_FALSE(uvs.generated);
    const std::vector<Eigen::Vector2d> suv = surfaceSampleUvs(s, shape->getMesh(), uvs.corner_uvs);
    for (TextureFilter filter : {TextureFilter::Nearest, TextureFilter::Bilinear}) {
        const std::vector<double> v = permeabilityFromImage(suv, img, filter);
        int wrong = 0;
        for (std::size_t i = 0; i < s.size(); ++i)
            if (std::abs(v[i] - red(boxFace(s, i)) / 255.0) > 1e-6) ++wrong;
        CHECK(wrong == 0);
        // Open area: the +y face (2 × 3 m²) fully, the +x face (1 × 3 m²) at 0.2.
        WaterGraph g;
        WaterNode n;
        n.name = "hold";
        n.capacity = 1;
        g.nodes = {n};
        const PermeableSamples holes = permeableSamplesFromValues(s, v, {}, g);
        CHECK(holes.totalOpenArea() == Approx(6.0 + 0.2 * 3.0).epsilon(1e-6));
    }
    fs::remove_all(dir);
}

TEST_CASE("a model without UVs uses the generated atlas, which the exported template and OBJ show", "[graph]") {
    const fs::path dir = tempDir("atlas");
    TriangleMesh mesh = makeBoxMesh(1.0, 1.0, 1.0);
    mesh.corner_uvs.clear();
    const int size = 64;
    const PermeabilityUvs uvs = permeabilityUvs(mesh, size);
    REQUIRE(uvs.generated);
    writeAtlasTemplatePng(uvs.corner_uvs, size, (dir / "template.png").string());
    writeAtlasObj(mesh, uvs.corner_uvs, (dir / "atlas.obj").string());
    // The template is sealed as written (red 0 everywhere)...
    const PermeabilityImage tmpl = loadPermeabilityImage((dir / "template.png").string());
    auto shape = btBuoyancyShape::create(mesh);
    const SurfaceSamples& s = shape->getDragSamples();
    const std::vector<Eigen::Vector2d> suv = surfaceSampleUvs(s, mesh, uvs.corner_uvs);
    double sum = 0;
    for (double v : permeabilityFromImage(suv, tmpl)) sum += v;
    CHECK(sum == 0.0);
    // ... and painting its charts red (grown by one texel, as a painter's brush would) opens the whole surface.
    PermeabilityImage painted;
    painted.width = painted.height = size;
    painted.value.assign(std::size_t(size) * size, 0.0f);
    // Covered texels: rasterise the atlas triangles here (centre inside), then grow by one texel.
    std::vector<unsigned char> covered(std::size_t(size) * size, 0);
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        Eigen::Vector2d p[3];
        for (int k = 0; k < 3; ++k) p[k] = Eigen::Vector2d(uvs.corner_uvs[3 * t + k].x() * size, (1 - uvs.corner_uvs[3 * t + k].y()) * size);
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const Eigen::Vector2d c(x + 0.5, y + 0.5);
                double d[3];
                for (int k = 0; k < 3; ++k) {
                    const Eigen::Vector2d e = p[(k + 1) % 3] - p[k], q = c - p[k];
                    d[k] = e.x() * q.y() - e.y() * q.x();
                }
                if ((d[0] >= 0 && d[1] >= 0 && d[2] >= 0) || (d[0] <= 0 && d[1] <= 0 && d[2] <= 0))
                    covered[std::size_t(y) * size + x] = 1;
            }
    }
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int xx = x + dx, yy = y + dy;
                    if (xx >= 0 && yy >= 0 && xx < size && yy < size && covered[std::size_t(yy) * size + xx])
                        painted.value[std::size_t(y) * size + x] = 1.0f;
                }
    const std::vector<double> v = permeabilityFromImage(suv, painted, TextureFilter::Nearest);
    double open = 0, area = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        open += v[i] * s.area[i];
        area += s.area[i];
    }
    CHECK(area == Approx(6.0));
    CHECK(open == Approx(area).epsilon(1e-12));
    // The OBJ carries one vt per corner and the faces reference them.
    std::ifstream obj(dir / "atlas.obj");
    std::string line;
    int vs = 0, vts = 0, fs_ = 0;
    while (std::getline(obj, line)) {
        if (line.rfind("v ", 0) == 0) ++vs;
        if (line.rfind("vt ", 0) == 0) ++vts;
        if (line.rfind("f ", 0) == 0) ++fs_;
    }
    CHECK(vs == int(mesh.vertices.size()));
    CHECK(vts == int(3 * mesh.triangleCount()));
    CHECK(fs_ == int(mesh.triangleCount()));
    fs::remove_all(dir);
}

TEST_CASE("permeability map: paint at run time, bad edits change nothing, a hit floods the hull", "[graph][bullet]") {
    const TriangleMesh mesh = makeBoxMesh(1, 1, 1);
    auto shape = btBuoyancyShape::create(mesh);
    WaterGraph g;
    WaterNode n;
    n.name = "hold";
    n.capacity = 0.8;
    g.nodes = {n};
    PermeabilityMap map(shape->getDragSamples(), g);
    CHECK(map.permeableSamples().size() == 0);  // sealed
    const std::vector<double> before = map.values();
    CHECK_THROWS_AS(map.setValue(map.size(), 0.5), std::invalid_argument);
    CHECK_THROWS_AS(map.setValue(0, 1.5), std::invalid_argument);
    CHECK_THROWS_AS(map.setValue(0, std::nan("")), std::invalid_argument);
    std::vector<double> bad(map.size(), 0.5);
    bad.back() = -0.1;  // one bad value at the end: nothing applied
    CHECK_THROWS_AS(map.setValues(bad), std::invalid_argument);
    CHECK_THROWS_AS(map.paintSphere(Eigen::Vector3d(0, -0.5, 0), -1, 1), std::invalid_argument);
    CHECK_THROWS_AS(map.paintSphere(Eigen::Vector3d(0, -0.5, 0), 0.2, 2), std::invalid_argument);
    CHECK_THROWS_AS(map.paintSphere(Eigen::Vector3d(0, -0.5, 0), 0.2, 1, PermeabilityPaint::Max, 3), std::invalid_argument);
    CHECK_THROWS_AS(map.paintSphere(Eigen::Vector3d(std::nan(""), 0, 0), 0.2, 1), std::invalid_argument);
    CHECK(map.values() == before);

    // A world: the box hull (dry mass 300 kg, ρ_w V_material = 200 kg) floats sealed, then a hit opens its bottom.
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher(&config);
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
    world.setGravity(btVector3(0, btScalar(-9.81), 0));
    btFlatWaterSurface surface(0.0);
    btBuoyancyWorld water(&surface, 1000.0, 9.81);
    btBuoyantBodySettings bs;
    bs.mass = 300;
    btTransform pose;
    pose.setIdentity();
    btBuoyantBody body(shape, bs, pose);
    world.addRigidBody(body.getRigidBody());
    btBuoyancyAction action(body, &water);
    world.addAction(&action);
    btFloodingAction flood(body, &water, g, map.permeableSamples());
    world.addAction(&flood);
    auto run = [&](double seconds) {
        for (int i = 0; i < int(seconds * 60); ++i) world.stepSimulation(btScalar(1.0 / 60), 4, btScalar(1.0 / 240));
    };
    run(2);
    CHECK(flood.getWaterVolume() == 0.0);
    // Bad run-time edits through the action leave its holes as they were.
    WaterGraph other = g;
    WaterNode n2 = n;
    n2.name = "other";
    n2.position = Eigen::Vector3d(0.3, 0, 0);
    other.nodes.push_back(n2);
    PermeabilityMap wrongGraph(shape->getDragSamples(), other);
    wrongGraph.paintSphere(Eigen::Vector3d(0.3, 0, 0), 2.0, 1.0);  // feeds node 1, which this body lacks
    CHECK_THROWS_AS(flood.setPermeability(wrongGraph), std::invalid_argument);
    CHECK(flood.getPermeableSamples().size() == 0);
    // The hit: open a 0.25 m hole under the keel.
    const std::size_t hit = map.paintSphere(Eigen::Vector3d(0, -0.5, 0), 0.25, 1.0);
    CHECK(hit > 0);
    flood.setPermeability(map);
    CHECK(flood.getPermeableSamples().size() == hit);
    run(20);
    // 300 kg > ρ_w V_material = 1000 (1 − 0.8) = 200 kg: it floods (design.md 5).
    CHECK(flood.getWaterVolume() > 0.1);
    world.removeAction(&flood);
    world.removeAction(&action);
    world.removeRigidBody(body.getRigidBody());
}

TEST_CASE("scene key permeability.texture: the painted bottom floods, errors name key and file", "[graph][cli]") {
    const fs::path dir = tempDir("scene");
    // Box charts: the −y face is face 2 → block column 2, bottom row.
    writePng(dir / "hull_damage.png", 30, 20, 3, [](int x, int y, int c) { return c == 0 && x / 10 == 2 && y / 10 == 1 ? 255 : 0; });
    writePng(dir / "sealed.png", 30, 20, 3, [](int, int, int) { return 0; });
    writePng(dir / "grey.png", 8, 8, 1, [](int, int, int) { return 255; });
    auto sceneText = [](const std::string& texture) {
        return R"({"duration": 6, "output_interval": 1, "bodies": [{"name": "hull", "shape": {"type": "box", "size": [1, 1, 1]},
                  "mass": 300, "water_graph": {"nodes": [{"name": "hold", "capacity": 0.8}]},
                  "permeability": {"texture": ")" + texture + R"(", "filter": "nearest"}}]})";
    };
    auto runScene = [&](const std::string& texture) {
        { std::ofstream(dir / "s.json") << sceneText(texture); }
        REQUIRE(cli::runSceneCommand((dir / "s.json").string(), (dir / "out").string(), std::nullopt) == 0);
        std::ifstream in(dir / "out" / "trajectory.csv");
        std::string header, line, last;
        std::getline(in, header);
        while (std::getline(in, line)) last = line;
        // water_volume column
        std::stringstream hs(header), ls(last);
        std::string h, v;
        double water = -1;
        while (std::getline(hs, h, ',') && std::getline(ls, v, ','))
            if (h == "water_volume") water = std::stod(v);
        return water;
    };
    CHECK(runScene("hull_damage.png") > 0.05);
    CHECK(runScene("sealed.png") == 0.0);
    auto parseError = [&](const std::string& texture) {
        return errorOf([&] { cli::parseScene(sceneText(texture), "s.json", dir.string()); });
    };
    CHECK_THAT(parseError("nothere.png"), Catch::Contains("bodies[0].permeability.texture") && Catch::Contains("nothere.png"));
    CHECK_THAT(parseError("grey.png"), Catch::Contains("bodies[0].permeability.texture") && Catch::Contains("grey.png") &&
                                           Catch::Contains("channel"));
    CHECK_THAT(parseError(""), Catch::Contains("bodies[0].permeability.texture"));
    fs::remove_all(dir);
}

// Regression (found by fuzz_permeability_image): a PNG whose first IDAT chunk is empty made stb_image 2.27
// copy 0 bytes from a null buffer (undefined behaviour; UBSan stopped the fuzzer). The decoder drops empty IDAT
// chunks first: they hold no image data, so the image is the same with or without them.
TEST_CASE("permeability image: empty IDAT chunks change nothing (fuzz regression)", "[graph][fuzz-regression]") {
    // The fuzzer's input, 99 bytes: a 4 x 3 RGBA PNG with an empty IDAT before a corrupt one.
    const unsigned char found[] = {
        0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
        0x00, 0x04, 0x00, 0x00, 0x00, 0x03, 0x08, 0x06, 0x00, 0x00, 0x00, 0x10, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
        0x00, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x15, 0xc8, 0x00, 0xb4, 0xf4, 0xae, 0xc6, 0x00, 0x00, 0x00, 0xd8,
        0x43, 0xc4, 0x0b, 0x3b, 0x39, 0xc8, 0x39, 0x07, 0x50, 0x86, 0x2c, 0x01, 0xd6, 0xdd, 0x8a, 0x2a, 0x18, 0x43,
        0x51, 0xe7, 0xc7, 0x31, 0x14, 0x55, 0x0f, 0xf1, 0x36, 0x16, 0x99, 0x33, 0x3f, 0xb8, 0xec, 0x00, 0x00, 0x00,
        0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
    // Decodes or is refused with a clear error; never undefined behaviour (the sanitizer build runs this too).
    try {
        const PermeabilityImage img = decodePermeabilityImage(found, sizeof found, "found.png");
        CHECK(img.width == 4);
        CHECK(img.height == 3);
    } catch (const std::invalid_argument& e) {
        CHECK_THAT(e.what(), Catch::Matchers::StartsWith("found.png: "));
    }

    // A valid PNG with empty IDAT chunks inserted before its first IDAT and before IEND decodes to the same texels.
    const fs::path dir = tempDir("empty-idat");
    writePng(dir / "img.png", 3, 2, 3, [](int x, int y, int c) { return c == 0 ? 51 * (3 * y + x) : 9 * c; });
    std::ifstream in(dir / "img.png", std::ios::binary);
    const std::vector<unsigned char> png((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    REQUIRE(png.size() > 33);
    // An empty chunk: length 0, type IDAT, CRC-32 of "IDAT" (ISO 3309, as PNG specifies), computed here.
    std::uint32_t crc = 0xFFFFFFFFu;
    for (unsigned char ch : std::string("IDAT")) {
        crc ^= ch;
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    crc ^= 0xFFFFFFFFu;
    const unsigned char empty[12] = {0, 0, 0, 0, 'I', 'D', 'A', 'T', (unsigned char)(crc >> 24), (unsigned char)(crc >> 16),
                                     (unsigned char)(crc >> 8), (unsigned char)crc};
    std::vector<unsigned char> padded(png.begin(), png.begin() + 33);  // signature + IHDR (stb writes IDAT next)
    padded.insert(padded.end(), empty, empty + 12);
    padded.insert(padded.end(), png.begin() + 33, png.end() - 12);  // up to IEND
    padded.insert(padded.end(), empty, empty + 12);
    padded.insert(padded.end(), png.end() - 12, png.end());
    REQUIRE(std::equal(png.begin() + 37, png.begin() + 41, "IDAT"));
    const PermeabilityImage a = decodePermeabilityImage(png.data(), png.size(), "plain.png");
    const PermeabilityImage b = decodePermeabilityImage(padded.data(), padded.size(), "padded.png");
    REQUIRE(b.width == 3);
    REQUIRE(b.height == 2);
    CHECK(b.value == a.value);
    for (int i = 0; i < 6; ++i) CHECK(b.value[std::size_t(i)] == Approx(51.0 * i / 255.0).margin(1e-6));
}
