// `buoyancy run` with any gravity: a Z-up scene file and an oblique one (with "water.frame") give the Y-up scene's
// trajectory rotated (the oracle: the Y-up run of the same scene); Moon and zero gravity; every refusal of a water
// frame with its message. The executable is run as a user runs it.
#include "CliRunner.h"

#include <LinearMath/btScalar.h>
#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

using buoyancy_test::runCli;
using buoyancy_test::scratchDir;
using Catch::Matchers::Contains;

namespace {

constexpr bool kDouble = sizeof(btScalar) == sizeof(double);

std::string vec(const Eigen::Vector3d& v) {
    std::ostringstream s;
    s.precision(17);
    s << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
    return s.str();
}

/// A body's "rotation" key for the orientation Q·R(axis, degrees).
std::string rotation(const Eigen::Matrix3d& Q, const Eigen::Vector3d& axis, double degrees) {
    const Eigen::AngleAxisd r(Q * Eigen::AngleAxisd(degrees * M_PI / 180.0, axis).toRotationMatrix());
    std::ostringstream s;
    s.precision(17);
    s << R"({"axis": )" << vec(r.angle() > 0 ? r.axis() : Eigen::Vector3d::UnitY()) << R"(, "degrees": )"
      << r.angle() * 180.0 / M_PI << "}";
    return s.str();
}

/// A scene with two bodies (a box dropped 0.2 m, a heeled board) in flat water, mapped by the rotation Q:
/// gravity Q(0, −g, 0), positions Q p, orientations Q R, the water frame (up Q ŷ, x Q x̂) when `frame` is true.
std::string sceneText(const Eigen::Matrix3d& Q, double g, bool frame, double duration = 6.0) {
    std::ostringstream s;
    s << R"({"gravity": )" << vec(Q * Eigen::Vector3d(0, -g, 0))
      << R"(, "dt": 0.004166666666666667, "substeps_per_frame": 4, "duration": )" << duration
      << R"(, "output_interval": 0.5, "water": {"type": "flat", "height": 0, "density": 1000)";
    if (frame) s << R"(, "frame": {"up": )" << vec(Q.col(1)) << R"(, "x": )" << vec(Q.col(0)) << "}";
    s << R"(}, "bodies": [)"
      << R"({"name": "box", "shape": {"type": "box", "size": [1, 0.5, 0.8]}, "density": 500, "position": )"
      << vec(Q * Eigen::Vector3d(-2, 0.2, 0)) << R"(, "rotation": )" << rotation(Q, Eigen::Vector3d::UnitY(), 0) << "},"
      << R"({"name": "board", "shape": {"type": "box", "size": [1.2, 0.3, 0.8]}, "density": 400, "position": )"
      << vec(Q * Eigen::Vector3d(2, 0.03, 0)) << R"(, "rotation": )" << rotation(Q, Eigen::Vector3d::UnitX(), 15)
      << "}]}";
    return s.str();
}

struct Row {
    std::string body;
    Eigen::Vector3d com;
    Eigen::Quaterniond q;
    double submerged = 0;
    double water = 0;  ///< m³ inside the body (water graph)
};

/// Run `text` as DIR/name.json; the trajectory's rows (exit code checked).
std::vector<Row> runScene(const std::string& dir, const std::string& name, const std::string& text) {
    const std::string path = dir + "/" + name + ".json";
    std::ofstream(path) << text;
    const auto r = runCli({"run", path, "--out", dir + "/" + name, "--quiet"});
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    std::ifstream in(dir + "/" + name + "/trajectory.csv");
    std::string line;
    std::getline(in, line);
    std::vector<Row> rows;
    while (std::getline(in, line)) {
        std::stringstream ss(line);
        std::string cell;
        std::vector<double> v;
        Row row;
        std::getline(ss, cell, ',');
        std::getline(ss, row.body, ',');
        while (std::getline(ss, cell, ',')) v.push_back(std::stod(cell));
        // columns after body: x y z qx qy qz qw cx cy cz vx vy vz wx wy wz submerged_volume ...
        row.q = Eigen::Quaterniond(v[6], v[3], v[4], v[5]);
        row.com = Eigen::Vector3d(v[7], v[8], v[9]);
        row.submerged = v[16];
        row.water = v[18];
        rows.push_back(row);
    }
    return rows;
}

/// Largest distance (m) and angle (rad) between the Y-up rows and the mapped rows mapped back by Qᵀ.
std::pair<double, double> deviation(const std::vector<Row>& yUp, const std::vector<Row>& mapped, const Eigen::Matrix3d& Q) {
    REQUIRE(yUp.size() == mapped.size());
    double d = 0, a = 0;
    for (std::size_t i = 0; i < yUp.size(); ++i) {
        d = std::max(d, (Q.transpose() * mapped[i].com - yUp[i].com).norm());
        const Eigen::Matrix3d back = Q.transpose() * mapped[i].q.toRotationMatrix();
        a = std::max(a, Eigen::AngleAxisd(yUp[i].q.toRotationMatrix().transpose() * back).angle());
    }
    return {d, a};
}

std::string refusal(const std::string& dir, const std::string& name, const std::string& text) {
    const std::string path = dir + "/" + name + ".json";
    std::ofstream(path) << text;
    const auto r = runCli({"run", path, "--out", dir + "/" + name});
    CHECK(r.exit_code == 2);
    return r.err;
}

}  // namespace

TEST_CASE("buoyancy run: a Z-up scene and an oblique one give the Y-up trajectory rotated", "[cli][upaxis]") {
    // The same two bodies in a Y-up scene, its Z-up copy (gravity [0, 0, -9.81], no "frame": the default one, x
    // first) and an oblique copy with an explicit "water.frame". Positions in the CSV are shortest round-trip decimals
    // of the state: in double the runs agree to rounding (1e-6 m, 1e-6 rad); float rounds every pose to 6e-8 relative
    // and the difference grows with the motion (bar 5e-4 m, 5e-4 rad, as the library's property test).
    const std::string dir = scratchDir("run_upaxis");
    const auto yUp = runScene(dir, "yup", sceneText(Eigen::Matrix3d::Identity(), 9.81, false));
    Eigen::Matrix3d zUp;
    zUp << 1, 0, 0, 0, 0, -1, 0, 1, 0;  // y → z, z → −y: the default frame of gravity −z
    const Eigen::Matrix3d oblique = Eigen::AngleAxisd(1.1, Eigen::Vector3d(2, -1, 0.5).normalized()).toRotationMatrix();
    const double bar = kDouble ? 1e-6 : 5e-4;
    for (const auto& [name, Q, frame] : {std::make_tuple(std::string("zup"), zUp, false),
                                         std::make_tuple(std::string("oblique"), oblique, true)}) {
        const auto mapped = runScene(dir, name, sceneText(Q, 9.81, frame));
        const auto [d, a] = deviation(yUp, mapped, Q);
        INFO(name << ": " << d << " m, " << a << " rad");
        CHECK(d <= bar);
        CHECK(a <= bar);
    }
    // The Y-up box came down near its draft: half of 0.4 m³ under water, still heaving by a few % at 6 s (the oracle
    // itself is sane).
    CHECK(yUp[yUp.size() - 2].submerged == Approx(0.2).epsilon(0.05));
}

TEST_CASE("buoyancy run: Moon gravity in a Z-up scene floats at the Archimedes draft, zero gravity runs without NaN",
          "[cli][upaxis]") {
    const std::string dir = scratchDir("run_upaxis_g");
    Eigen::Matrix3d zUp;
    zUp << 1, 0, 0, 0, 0, -1, 0, 1, 0;
    const auto moon = runScene(dir, "moon", sceneText(zUp, 1.62, false, 20.0));
    // Archimedes: V_sub = m / ρ whatever g (box 0.2 of 0.4 m³, board 0.4 × 0.288 m³).
    CHECK(moon[moon.size() - 2].submerged == Approx(0.2).epsilon(0.01));
    CHECK(moon.back().submerged == Approx(0.1152).epsilon(0.01));
    const auto none = runScene(dir, "zero", sceneText(zUp, 0.0, false, 2.0));
    for (const Row& r : none) {
        CHECK(r.com.allFinite());
        CHECK(r.submerged == 0.0);  // no pressure gradient: nothing computed
    }
    CHECK((none.back().com - none[1].com).norm() < 1e-9);  // nothing moves the bodies (they start at rest)
}

TEST_CASE("buoyancy run: water frames are checked, each refusal names the key and the vectors", "[cli][upaxis]") {
    const std::string dir = scratchDir("run_upaxis_bad");
    const std::string body = R"("bodies": [{"shape": {"type": "box", "size": [1, 1, 1]}, "density": 500}]})";
    CHECK_THAT(refusal(dir, "against", R"({"gravity": [0, 0, -9.81], "water": {"frame": {"up": [0, 1, 0]}}, )" + body),
               Contains("against.json: water.frame.up: (0, 1, 0) is not antiparallel to the scene's gravity "
                        "(0, 0, -9.81) m/s^2 (1.5708 rad apart, 1e-6 allowed)"));
    CHECK_THAT(refusal(dir, "tilted", R"({"gravity": [0, 0, -9.81], "water": {"frame": {"up": [0, 0.001, 1]}}, )" + body),
               Contains("water.frame.up: (0, 0.001, 1) is not antiparallel to the scene's gravity (0, 0, -9.81)"));
    CHECK_THAT(refusal(dir, "notperp", R"({"gravity": [0, 0, -9.81], "water": {"frame": {"up": [0, 0, 1], "x": [1, 0, 0.1]}}, )" + body),
               Contains("water.frame.x: x axis (1, 0, 0.1) is not perpendicular to up (0, 0, 1)"));
    CHECK_THAT(refusal(dir, "zero", R"({"water": {"frame": {"up": [0, 0, 0]}}, )" + body),
               Contains("water.frame.up: zero vector"));
    CHECK_THAT(refusal(dir, "key", R"({"water": {"frame": {"up": [0, 1, 0], "y": [1, 0, 0]}}, )" + body),
               Contains("water.frame"));
    CHECK_THAT(refusal(dir, "ground", R"({"gravity": [0, 0, -9.81], "ground": {"height": -2, "normal": [0, 1, 0]}, )" + body),
               Contains("ground.normal: must point up"));
}

TEST_CASE("buoyancy run: a flooding body in a Z-up scene fills and sinks as in the Y-up scene", "[cli][upaxis]") {
    // A 2 × 1 × 1 m box of 300 kg with one compartment and a hole in its bottom (mesh frame: unchanged by the
    // rotation): the water graph's levels are along up in the water frame, so the water let in over 3 s is the same.
    auto text = [](const Eigen::Matrix3d& Q) {
        std::ostringstream s;
        s << R"({"gravity": )" << vec(Q * Eigen::Vector3d(0, -9.81, 0))
          << R"(, "duration": 3, "output_interval": 0.5, "bodies": [{"name": "hull", "shape": {"type": "box",)"
          << R"( "size": [2, 1, 1]}, "mass": 300, "position": )" << vec(Q * Eigen::Vector3d(0, 0.4, 0))
          << R"(, "rotation": )" << rotation(Q, Eigen::Vector3d::UnitY(), 0)
          << R"(, "water_graph": {"nodes": [{"name": "hold", "position": [0, 0, 0], "capacity": 1.0}], "edges": [],)"
          << R"( "seed": 1}, "permeability": {"regions": [{"centre": [0, -0.5, 0], "radius": 0.3, "value": 1.0}]}}]})";
        return s.str();
    };
    const std::string dir = scratchDir("run_upaxis_flood");
    const auto yUp = runScene(dir, "yup", text(Eigen::Matrix3d::Identity()));
    Eigen::Matrix3d zUp;
    zUp << 1, 0, 0, 0, 0, -1, 0, 1, 0;
    const auto mapped = runScene(dir, "zup", text(zUp));
    REQUIRE(yUp.size() == mapped.size());
    CHECK(yUp.back().water > 0.05);  // water came in
    double worst = 0;
    for (std::size_t i = 0; i < yUp.size(); ++i) worst = std::max(worst, std::abs(yUp[i].water - mapped[i].water));
    const auto [d, a] = deviation(yUp, mapped, zUp);
    INFO("water " << worst << " m^3, " << d << " m, " << a << " rad");
    CHECK(worst <= (kDouble ? 1e-6 : 5e-4));
    CHECK(d <= (kDouble ? 1e-6 : 5e-4));
}
