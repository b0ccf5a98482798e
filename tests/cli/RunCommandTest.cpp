// What `buoyancy run` tells its user, end to end (the executable run as a user runs it, stdout and stderr captured,
// so stderr is not a terminal): progress lines, the level-of-detail lines and their summary past 8 bodies, the
// summary table, --quiet, and the trajectory's numbers (shortest round-trip decimals, no negative zero);
// `buoyancy --version`; the progress bar of a terminal through ProgressReporter itself.
#include "CliRunner.h"
#include "cli/Progress.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

using buoyancy_test::runCli;
using buoyancy_test::scratchDir;
using Catch::Matchers::Contains;

namespace {

const std::string kScenes = std::string(BUOYANCY_SOURCE_DIR) + "/bullet_examples/scenes/";

std::vector<std::string> splitLines(const std::string& text) {
    std::vector<std::string> lines;
    std::stringstream ss(text);
    for (std::string line; std::getline(ss, line);) lines.push_back(line);
    return lines;
}

/// A scene of `count` small boxes of density 500 kg/m³ in flat water, 1 s.
std::string writeBoxesScene(const std::string& dir, int count) {
    const std::string path = dir + "/boxes.json";
    std::ofstream f(path);
    f << R"({"gravity": [0, -9.81, 0], "dt": 0.004166666666666667, "substeps_per_frame": 4, "duration": 1,)"
      << R"( "output_interval": 0.25, "water": {"type": "flat", "height": 0.0, "density": 1000}, "bodies": [)";
    for (int i = 0; i < count; ++i)
        f << (i ? "," : "") << R"({"name": "box)" << i << R"(", "shape": {"type": "box", "size": [0.5, 0.5, 0.5]},)"
          << R"( "density": 500, "position": [)" << 2.0 * i << ", 0.1, 0]}";
    f << "]}\n";
    return path;
}

/// True when `text` is the shortest decimal that reads back to its value: one significant digit fewer, rounded
/// either way, reads back to a different double (an independent check of std::to_chars' shortest form).
bool isShortestRoundTrip(const std::string& text) {
    const double v = std::strtod(text.c_str(), nullptr);
    if (v == 0.0) return text == "0";
    std::string mantissa = text.substr(0, text.find_first_of("eE"));
    const bool integer = mantissa.find('.') == std::string::npos && mantissa.size() == text.size();
    std::string digits;
    for (char c : mantissa)
        if (c >= '0' && c <= '9') digits += c;
    digits.erase(0, digits.find_first_not_of('0'));
    if (integer) digits.erase(digits.find_last_not_of('0') + 1);  // "100": one significant digit
    if (digits.size() <= 1) return true;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*e", int(digits.size()) - 2, v);  // one significant digit fewer, nearest
    return std::strtod(buf, nullptr) != v;
}

}  // namespace

TEST_CASE("buoyancy --version prints the project's version and exits 0", "[cli]") {
    const auto r = runCli({"--version"});
    CHECK(r.exit_code == 0);
    CHECK(r.out == std::string("buoyancy ") + BUOYANCY_PROJECT_VERSION + "\n");
}

TEST_CASE("buoyancy run: progress lines, level of detail, summary, and --quiet silences them", "[cli]") {
    const std::string dir = scratchDir("run_talks");
    SECTION("one body: a progress line per 10 %, one level-of-detail line, the summary table") {
        const auto r = runCli({"run", kScenes + "plank.json", "--out", dir + "/plank", "--duration", "2"});
        INFO("stderr: " << r.err);
        REQUIRE(r.exit_code == 0);
        CHECK_THAT(r.err, Contains("body plank: level of detail"));
        int progressLines = 0;
        for (const auto& line : splitLines(r.err))
            if (line.rfind("run plank.json: ", 0) == 0) ++progressLines;
        CHECK(progressLines >= 2);   // at least one step and the final 100 %
        CHECK(progressLines <= 11);  // every 10 % at most (the run takes far less than 30 s)
        CHECK_THAT(r.err, Contains("run plank.json: 100 % (2 of 2 s simulated)"));
        CHECK(r.err.find("100 %") == r.err.rfind("100 %"));  // once
        CHECK(r.err.find('\r') == std::string::npos);  // no bar when stderr is not a terminal
        CHECK_THAT(r.out, Contains("summary (t = 0 .. 2 s, 21 rows per body)"));
        CHECK_THAT(r.out, Contains("final position (x, y, z) m"));
        const std::regex row(R"(\nplank +\(-?[0-9.]+, -?[0-9.]+, -?[0-9.]+\) +-?[0-9.]+ \.\. -?[0-9.]+ +[0-9.]+ +[0-9.]+\n)");
        CHECK(std::regex_search(r.out, row));
        CHECK(r.out.find("-0.00") == std::string::npos);  // tiny negatives print as 0.00 (the plank stays at x = z = 0)
    }
    SECTION("--quiet: nothing on stdout or stderr, the same trajectory") {
        const auto loud = runCli({"run", kScenes + "plank.json", "--out", dir + "/loud", "--duration", "1"});
        const auto quiet = runCli({"run", kScenes + "plank.json", "--out", dir + "/quiet", "--duration", "1", "--quiet"});
        REQUIRE(loud.exit_code == 0);
        REQUIRE(quiet.exit_code == 0);
        CHECK(quiet.out.empty());
        CHECK(quiet.err.empty());
        std::ifstream a(dir + "/loud/trajectory.csv"), b(dir + "/quiet/trajectory.csv");
        std::stringstream sa, sb;
        sa << a.rdbuf();
        sb << b.rdbuf();
        CHECK(sa.str() == sb.str());
        CHECK(!sa.str().empty());
    }
    SECTION("past 8 bodies: one level-of-detail summary, not a line per body; the table becomes a spread") {
        const auto r = runCli({"run", writeBoxesScene(dir, 24), "--out", dir + "/boxes"});
        INFO("stderr: " << r.err);
        REQUIRE(r.exit_code == 0);
        CHECK_THAT(r.err, Contains("24 floating bodies; level of detail:"));
        CHECK_THAT(r.err, Contains("  24 x "));
        CHECK(r.err.find("body box0: level of detail") == std::string::npos);
        CHECK_THAT(r.out, Contains("24 bodies"));
        CHECK_THAT(r.out, Contains("heave amplitude"));
        CHECK(r.out.find("\nbox3 ") == std::string::npos);
    }
    SECTION("8 bodies still get a line each") {
        const auto r = runCli({"run", writeBoxesScene(dir, 8), "--out", dir + "/eight"});
        REQUIRE(r.exit_code == 0);
        for (int i = 0; i < 8; ++i) CHECK_THAT(r.err, Contains("body box" + std::to_string(i) + ": level of detail"));
    }
}

TEST_CASE("buoyancy run: trajectory numbers are shortest round-trip decimals, never -0", "[cli]") {
    const std::string dir = scratchDir("run_numbers");
    const auto r = runCli({"run", kScenes + "plank.json", "--out", dir, "--duration", "1", "--quiet"});
    REQUIRE(r.exit_code == 0);
    std::ifstream f(dir + "/trajectory.csv");
    std::string header;
    REQUIRE(std::getline(f, header));
    int fields = 0, rows = 0;
    bool sawTenth = false;
    for (std::string line; std::getline(f, line);) {
        ++rows;
        std::stringstream ss(line);
        std::string cell;
        int column = 0;
        while (std::getline(ss, cell, ',')) {
            if (column++ == 1) continue;  // the body's name
            ++fields;
            INFO("row " << rows << " column " << column << ": " << cell);
            char* end = nullptr;
            std::strtod(cell.c_str(), &end);
            REQUIRE(end != cell.c_str());
            CHECK(*end == '\0');
            CHECK((cell.rfind("-0", 0) != 0 || cell.find_first_of("123456789") != std::string::npos));
            CHECK(isShortestRoundTrip(cell));
            if (column == 1 && cell == "0.1") sawTenth = true;
        }
    }
    CHECK(rows == 11);
    CHECK(fields > 0);
    CHECK(sawTenth);  // the time 0.1 s is written "0.1", not 0.10000000000000001
}

TEST_CASE("buoyancy hydrostatics: a dry body's zero results are written without a minus sign", "[cli]") {
    const std::string obj = scratchDir("dry_box") + "/box.obj";
    buoyancy_test::writeBoxObj(obj, 1.0, 1.0, 1.0);
    // Entirely above the water, rotated so that rounding leaves signed zeros in the products.
    const auto r = runCli({"hydrostatics", obj, "--water-height", "-5", "--rotate", "1", "1", "0", "30"});
    REQUIRE(r.exit_code == 0);
    const std::regex negativeZero(R"((^|[^0-9.eE])-0(\.0*)?([^0-9.]|$))");
    for (const auto& line : splitLines(r.out)) {
        INFO(line);
        CHECK_FALSE(std::regex_search(line, negativeZero));
    }
    CHECK_THAT(r.out, Contains("waterline area     0 m^2"));
    const auto j = runCli({"hydrostatics", obj, "--water-height", "-5", "--rotate", "1", "1", "0", "30", "--json"});
    REQUIRE(j.exit_code == 0);
    CHECK_FALSE(std::regex_search(j.out, std::regex(R"([^0-9.eE]-0(\.0+)?([^0-9.]|$))")));
}

TEST_CASE("progress: a bar redrawn in place on a terminal, lines every 10 % otherwise, nothing when quiet", "[cli]") {
    using buoyancy::cli::ProgressReporter;
    auto capture = [](ProgressReporter::Mode mode) {
        std::FILE* f = std::tmpfile();
        REQUIRE(f != nullptr);
        {
            ProgressReporter p("job", 100.0, " steps", mode, f);
            for (int i = 1; i <= 100; ++i) p.update(i);
            p.finish();
            p.finish();  // safe twice
        }
        std::rewind(f);
        std::string text;
        for (int c; (c = std::fgetc(f)) != EOF;) text += char(c);
        std::fclose(f);
        return text;
    };
    const std::string lines = capture(ProgressReporter::Mode::Lines);
    const auto all = splitLines(lines);
    CHECK(all.size() >= 2);
    CHECK(all.size() <= 11);  // deciles 1..10 and the final line, never more than one per decile
    CHECK_THAT(lines, Contains("job: 100 % (100 of 100 steps)"));
    CHECK(lines.find('\r') == std::string::npos);
    const std::string bar = capture(ProgressReporter::Mode::Terminal);
    CHECK_THAT(bar, Contains("\rjob [##############################] 100 %"));
    CHECK(bar.back() == '\n');
    CHECK(capture(ProgressReporter::Mode::Quiet).empty());
    CHECK(ProgressReporter::formatDuration(5.2) == "5 s");
    CHECK(ProgressReporter::formatDuration(185) == "3 min 05 s");
    CHECK(ProgressReporter::formatDuration(3720) == "1 h 02 min");
}

TEST_CASE("buoyancy run: a mesh file over 1 km gets a size warning with a \"scale\" hint, and runs", "[cli]") {
    const std::string dir = scratchDir("run_model_size");
    buoyancy_test::writeBoxObj(dir + "/crate_mm.obj", 1000, 500, 800);  // a 1 m crate written in millimetres
    std::ofstream(dir + "/scene.json")
        << R"({"duration": 0.1, "water": {"type": "flat"}, "bodies": [{"name": "crate", "shape": {"type": "mesh", )"
        << R"("file": "crate_mm.obj", "scale": 0.01}, "density": 500, "position": [0, 0, 0]}]})";
    const auto r = runCli({"run", dir + "/scene.json", "--out", dir + "/out", "--quiet"});
    CHECK(r.exit_code == 0);
    // At scale 0.01 its largest side is 10 m: in range, no warning.
    CHECK(r.err.find("largest side") == std::string::npos);
    std::ofstream(dir + "/scene_mm.json")
        << R"({"duration": 0.1, "water": {"type": "flat"}, "bodies": [{"name": "crate", "shape": {"type": "mesh", )"
        << R"("file": "crate_mm.obj", "scale": 2}, "density": 500, "position": [0, 0, 0]}]})";
    const auto mm = runCli({"run", dir + "/scene_mm.json", "--out", dir + "/out_mm", "--quiet"});
    CHECK(mm.exit_code == 0);
    CHECK_THAT(mm.err, Contains("bodies[0].shape"));
    CHECK_THAT(mm.err, Contains("the model's largest side is 2000 m"));
    CHECK_THAT(mm.err, Contains("\"scale\": 0.002"));
}

TEST_CASE("buoyancy bench: a progress line per part done", "[cli]") {
    const std::string dir = scratchDir("bench_progress");
    const auto r = runCli({"bench", "--quick", "--parts", "fig9,lod", "--out", dir});
    INFO("stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.err, Contains("bench:  50 % (1 of 2 parts)"));
    CHECK_THAT(r.err, Contains("bench: 100 % (2 of 2 parts)"));
}

namespace {

/// A crate (1 x 0.5 x 1 m, density 500) dropped with its bottom `drop` m above flat water; `events` is the scene's
/// "events" object ("" for none).
std::string writeDropScene(const std::string& dir, const std::string& name, double drop, const std::string& events) {
    const std::string path = dir + "/" + name + ".json";
    std::ofstream f(path);
    f << R"({"gravity": [0, -9.81, 0], "dt": 0.004166666666666667, "substeps_per_frame": 4, "duration": 3,)"
      << R"( "output_interval": 0.5, "water": {"type": "flat", "height": 0.0, "density": 1000},)"
      << (events.empty() ? "" : R"( "events": )" + events + ",")
      << R"( "bodies": [{"name": "crate", "shape": {"type": "box", "size": [1, 0.5, 1]}, "density": 500,)"
      << R"( "position": [0, )" << drop + 0.25 << R"(, 0]}]})" << '\n';
    return path;
}

struct EventRow {
    double t = 0, fraction = 0;
    std::string body, event, water;
};

std::vector<EventRow> readEvents(const std::string& path, std::string& header) {
    std::ifstream f(path);
    std::getline(f, header);
    std::vector<EventRow> rows;
    for (std::string line; std::getline(f, line);) {
        // t,substep,body,event,water_body,submerged_fraction
        EventRow r;
        std::stringstream ss(line);
        std::string t, substep, fraction;
        std::getline(ss, t, ',');
        std::getline(ss, substep, ',');
        std::getline(ss, r.body, ',');
        std::getline(ss, r.event, ',');
        std::getline(ss, r.water, ',');
        std::getline(ss, fraction, ',');
        r.t = std::strtod(t.c_str(), nullptr);
        r.fraction = std::strtod(fraction.c_str(), nullptr);
        rows.push_back(r);
    }
    return rows;
}

}  // namespace

TEST_CASE("buoyancy run: events.csv has the water events with the scene's hysteresis", "[cli]") {
    const std::string dir = scratchDir("run_events");
    const double drop = 1.0;  // the crate's bottom falls 1 m: it reaches the water at t = sqrt(2 drop / g)
    const double touch = std::sqrt(2 * drop / 9.81);
    std::string header;

    REQUIRE(runCli({"run", writeDropScene(dir, "default", drop, ""), "--out", dir + "/default", "--quiet"}).exit_code == 0);
    const std::vector<EventRow> rows = readEvents(dir + "/default/events.csv", header);
    CHECK(header == "t,substep,body,event,water_body,submerged_fraction");
    REQUIRE(!rows.empty());
    CHECK(rows[0].body == "crate");
    CHECK(rows[0].event == "enter_water");
    CHECK(rows[0].water == "water");
    // Enters at 1 % of its volume (the default), i.e. 5 mm deep at about 4.4 m/s: within a substep or two of the touch.
    CHECK(rows[0].t > touch);
    CHECK(rows[0].t < touch + 3 * 0.0042);
    CHECK(rows[0].fraction >= 0.01);
    for (const EventRow& r : rows) CHECK(r.event != "leave_water");  // it floats: never leaves

    // "events": enter at 30 % of the volume instead: later, at a larger fraction.
    REQUIRE(runCli({"run", writeDropScene(dir, "late", drop, R"({"enter_fraction": 0.3, "leave_fraction": 0.2})"),
                    "--out", dir + "/late", "--quiet"})
                .exit_code == 0);
    const std::vector<EventRow> late = readEvents(dir + "/late/events.csv", header);
    REQUIRE(!late.empty());
    CHECK(late[0].event == "enter_water");
    CHECK(late[0].fraction >= 0.3);
    CHECK(late[0].t > rows[0].t);
}

TEST_CASE("buoyancy run: bad \"events\" thresholds name the key", "[cli]") {
    const std::string dir = scratchDir("run_events_bad");
    struct Case {
        const char* events;
        const char* key;
    };
    for (const Case& c : {Case{R"({"leave_fraction": 0.5})", "events.leave_fraction"},
                          Case{R"({"enter_fraction": 1.5})", "events.enter_fraction"},
                          Case{R"({"surfaced_fraction": 0.995})", "events.surfaced_fraction"},
                          Case{R"({"enter": 0.5})", "events"},
                          Case{"0.5", "events"}}) {
        const auto r = runCli({"run", writeDropScene(dir, "bad", 1.0, c.events), "--out", dir + "/out", "--quiet"});
        INFO(c.events << " -> " << r.err);
        CHECK(r.exit_code == 2);
        CHECK_THAT(r.err, Contains(c.key));
        CHECK_THAT(r.err, Contains("bad.json"));
    }
}
