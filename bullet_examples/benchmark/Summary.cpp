#include "benchmark/Summary.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <cmath>
#include <sstream>

namespace buoyancy::bench {

namespace {

std::string fmt(const char* f, double x) {
    char b[64];
    std::snprintf(b, sizeof b, f, x);
    return b;
}

std::string label(const ConfigStats& c) {
    std::string s = c.method;
    if (c.method == "default") return s + " (" + c.variant + ")";
    if (c.texture > 0) s += " " + std::to_string(c.texture);
    if (!c.variant.empty()) s += " " + c.variant;
    return s;
}

/// The concrete configuration the default resolved to ("exact-mesh" or "exact-coverage-512").
bool isDefaultsOwn(const ConfigStats& c, const ConfigStats& def) {
    if (c.method == "default") return true;
    // An automatic-LOD row that picked the default's own configuration ("budget-1%:exact-mesh").
    if (c.method == "lod") {
        const std::size_t colon = c.variant.find(':');
        return colon != std::string::npos && c.variant.substr(colon + 1) == def.variant;
    }
    const std::string own = c.method + (c.texture > 0 ? "-" + std::to_string(c.texture) : "");
    return own == def.variant;
}

std::string ratio(double num, double den) { return den > 0 ? fmt("%.3g", num / den) : std::string("—"); }

/// The wave rows (and the flat rows of the same shapes' default) per shape and water: a table, the verdicts, and
/// the box in swell against the tangent plane.
std::string wavesMarkdown(const std::vector<ConfigStats>& all) {
    std::vector<std::pair<std::string, std::string>> groups;  // (shape, water), first-seen order
    for (const auto& c : all)
        if (std::find(groups.begin(), groups.end(), std::make_pair(c.shape, c.water)) == groups.end())
            groups.emplace_back(c.shape, c.water);
    bool anyWaves = false;
    for (const auto& g : groups) anyWaves = anyWaves || g.second != "flat";
    std::ostringstream md;
    md << "\n## In waves: worst errors over the poses, mean times (wave rows)\n\n";
    if (!anyWaves) {
        md << "Not measured in this run (part `waves`).\n";
        return md.str();
    }
    auto find = [&](const std::string& shape, const std::string& water, const std::string& method) -> const ConfigStats* {
        for (const auto& c : all)
            if (c.shape == shape && c.water == water && c.method == method) return &c;
        return nullptr;
    };
    md << "Errors against the wave reference (tests/oracles/WaveOracle); CoB moment = |ΔC_B| V_sub / (V · diagonal); "
          "ns/body-substep with drag on, ns hydrostatics with drag off (one thread).\n\n"
       << "| shape | water | configuration | poses | volume err % | CoB err % | CoB moment err | torque err % | "
          "ns/body-substep | ns hydrostatics | hydrostatics / default |\n"
       << "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const auto& g : groups) {
        if (g.second == "flat") continue;
        const ConfigStats* def = find(g.first, g.second, "default");
        for (const auto& c : all) {
            if (c.shape != g.first || c.water != g.second) continue;
            md << "| " << c.shape << " | " << c.water << " | " << label(c) << " | " << c.poses << " | "
               << fmt("%.2g", c.worstVolumePct) << " | " << fmt("%.2g", c.worstCobPct) << " | "
               << fmt("%.2g", c.worstCobMoment) << " | " << fmt("%.2g", c.worstTorquePct) << " | "
               << fmt("%.0f", c.meanNs) << " | "
               << (std::isfinite(c.meanNsHydrostatics) ? fmt("%.0f", c.meanNsHydrostatics) : std::string("")) << " | "
               << (def && std::isfinite(c.meanNsHydrostatics) ? ratio(c.meanNsHydrostatics, def->meanNsHydrostatics)
                                                               : std::string(""))
               << " |\n";
        }
    }

    md << "\n## Per shape and water: the default against the bars (volume ≤ " << fmt("%g", kVolumeBarPct)
       << " % of V, CoB first moment ≤ " << fmt("%g", kCobMomentBar)
       << "), and anything at least as accurate and > 10 % faster\n\n";
    bool barsHold = true, nothingFaster = true;
    for (const auto& g : groups) {
        const ConfigStats* def = find(g.first, g.second, "default");
        if (!def) continue;
        const bool volOk = def->worstVolumePct <= kVolumeBarPct, cobOk = def->worstCobMoment <= kCobMomentBar;
        barsHold = barsHold && volOk && cobOk;
        std::vector<std::string> beat;
        for (const auto& c : all) {
            if (c.shape != g.first || c.water != g.second || isDefaultsOwn(c, *def)) continue;
            if (!(c.worstVolumePct <= def->worstVolumePct && c.worstCobPct <= def->worstCobPct)) continue;
            if (c.meanNs * 1.1 < def->meanNs)
                beat.push_back(label(c) + " (" + fmt("%.2f", c.meanNs / def->meanNs) + "× the body-substep time)");
            else if (std::isfinite(c.meanNsHydrostatics) && std::isfinite(def->meanNsHydrostatics) &&
                     c.meanNsHydrostatics * 1.1 < def->meanNsHydrostatics)
                beat.push_back(label(c) + " (" + fmt("%.2f", c.meanNsHydrostatics / def->meanNsHydrostatics) +
                               "× the hydrostatics time)");
        }
        nothingFaster = nothingFaster && beat.empty();
        md << "- " << g.first << " in " << g.second << " (default = " << def->variant << ", " << def->poses
           << " poses): worst volume error " << fmt("%.2g", def->worstVolumePct) << " % (" << (volOk ? "within" : "ABOVE")
           << " the bar), worst CoB first-moment error " << fmt("%.2g", def->worstCobMoment) << " ("
           << (cobOk ? "within" : "ABOVE") << " the bar); "
           << (beat.empty() ? "nothing measured is at least as accurate and > 10 % faster" : "as accurate and faster:");
        for (std::size_t i = 0; i < beat.size(); ++i) md << (i ? "; " : " ") << beat[i];
        md << '\n';
    }
    md << "\nThe default within the bars on every shape and water: " << (barsHold ? "holds" : "does not hold")
       << ". Nothing at least as accurate and > 10 % faster, on every shape and water: "
       << (nothingFaster ? "holds" : "does not hold") << ".\n";

    // The Jolt-style tangent plane against the default on the 12-triangle box in the swell (same run).
    const ConfigStats* def = find("box", "swell", "default");
    const ConfigStats* tan = find("box", "swell", "tangent-plane");
    if (def && tan) {
        md << "\n### Box (12 triangles) in swell: the default against tangent-plane (same run)\n\n"
           << "- hydrostatics alone: default " << fmt("%.0f", def->meanNsHydrostatics) << " ns / tangent-plane "
           << fmt("%.0f", tan->meanNsHydrostatics) << " ns = " << ratio(def->meanNsHydrostatics, tan->meanNsHydrostatics)
           << " (body-substep with drag: " << fmt("%.0f", def->meanNs) << " / " << fmt("%.0f", tan->meanNs) << " ns = "
           << ratio(def->meanNs, tan->meanNs) << ")\n"
           << "- worst volume error: default " << fmt("%.2g", def->worstVolumePct) << " % / tangent-plane "
           << fmt("%.2g", tan->worstVolumePct) << " % = " << ratio(def->worstVolumePct, tan->worstVolumePct) << "\n"
           << "- worst CoB first-moment error: default " << fmt("%.2g", def->worstCobMoment) << " / tangent-plane "
           << fmt("%.2g", tan->worstCobMoment) << " = " << ratio(def->worstCobMoment, tan->worstCobMoment) << "\n"
           << "- worst torque error: default " << fmt("%.2g", def->worstTorquePct) << " % / tangent-plane "
           << fmt("%.2g", tan->worstTorquePct) << " % = " << ratio(def->worstTorquePct, tan->worstTorquePct) << "\n";
    }
    return md.str();
}

}  // namespace

std::vector<ConfigStats> reduceConfigs(const std::vector<SpeedErrorRow>& rows) {
    std::vector<ConfigStats> out;
    std::map<std::string, std::pair<std::size_t, int>> index;  // key -> (position, rows with ns_hydrostatics)
    for (const SpeedErrorRow& r : rows) {
        const std::string key =
            r.shape + "|" + r.water + "|" + r.method + "|" + std::to_string(r.texture) + "|" + r.variant;
        auto it = index.find(key);
        if (it == index.end()) {
            ConfigStats c;
            c.shape = r.shape;
            c.water = r.water;
            c.method = r.method;
            c.variant = r.variant;
            c.triangles = r.triangles;
            c.samples = r.samples;
            c.texture = r.texture;
            out.push_back(c);
            it = index.emplace(key, std::make_pair(out.size() - 1, 0)).first;
        }
        ConfigStats& c = out[it->second.first];
        c.worstVolumePct = std::max(c.worstVolumePct, r.volume_error_pct);
        c.worstCobPct = std::max(c.worstCobPct, r.cob_error_pct);
        c.worstTorquePct = std::max(c.worstTorquePct, r.torque_error_pct);
        c.worstCobMoment = std::max(c.worstCobMoment, r.cob_error_pct / 100.0 * r.submerged_fraction);
        const int n = ++c.poses;
        c.meanNs += (r.ns_per_body_substep - c.meanNs) / n;
        if (std::isfinite(r.ns_hydrostatics)) {
            const int h = ++it->second.second;
            c.meanNsHydrostatics += (r.ns_hydrostatics - c.meanNsHydrostatics) / h;
        }
    }
    for (const auto& kv : index)
        if (kv.second.second == 0) out[kv.second.first].meanNsHydrostatics = std::nan("");
    return out;
}

std::string summaryMarkdown(const std::vector<SpeedErrorRow>& rows, const std::vector<ScalingRow>& scaling) {
    const std::vector<ConfigStats> everything = reduceConfigs(rows);
    std::vector<ConfigStats> all;  // the flat-water configurations: the headline and the speed goals
    for (const auto& c : everything)
        if (c.water == "flat") all.push_back(c);
    std::vector<std::string> shapes;
    for (const auto& c : all)
        if (std::find(shapes.begin(), shapes.end(), c.shape) == shapes.end()) shapes.push_back(c.shape);
    auto find = [&](const std::string& shape, const std::string& method, int texture) -> const ConfigStats* {
        for (const auto& c : all)
            if (c.shape == shape && c.method == method && (texture < 0 || c.texture == texture)) return &c;
        return nullptr;
    };
    std::ostringstream md;
    md << "## Headline: worst errors over the poses, mean time per body-substep (drag on, one thread)\n\n"
       << "| shape | triangles | configuration | samples | volume err % | CoB err % | torque err % | ns/body-substep | time / default |\n"
       << "|---|---:|---|---:|---:|---:|---:|---:|---:|\n";
    for (const auto& s : shapes) {
        const ConfigStats* def = find(s, "default", -1);
        for (const ConfigStats* c : {def, find(s, "texel-centre", 1024), find(s, "exact-coverage", 128), find(s, "exact-mesh", 0)}) {
            if (!c) continue;
            md << "| " << s << " | " << c->triangles << " | " << label(*c) << " | " << c->samples << " | "
               << fmt("%.2g", c->worstVolumePct) << " | " << fmt("%.2g", c->worstCobPct) << " | "
               << fmt("%.2g", c->worstTorquePct) << " | " << fmt("%.0f", c->meanNs) << " | "
               << (def ? fmt("%.2f", c->meanNs / def->meanNs) : "") << " |\n";
        }
    }

    md << "\n## Nothing at least as accurate is more than 10 % faster than the default\n\n";
    bool p1 = true;
    for (const auto& s : shapes) {
        const ConfigStats* def = find(s, "default", -1);
        if (!def) continue;
        const bool high = def->triangles >= 10000;
        std::vector<std::string> beat, close;
        for (const auto& c : all) {
            if (c.shape != s || isDefaultsOwn(c, *def)) continue;
            const bool asAccurate = c.worstVolumePct <= def->worstVolumePct && c.worstCobPct <= def->worstCobPct;
            if (!asAccurate) continue;
            if (c.meanNs * 1.1 < def->meanNs) beat.push_back(label(c) + " (" + fmt("%.2f", c.meanNs / def->meanNs) + "× the time)");
            else if (high && c.meanNs < 2.0 * def->meanNs)
                close.push_back(label(c) + " (" + fmt("%.2f", c.meanNs / def->meanNs) + "× the time)");
        }
        const bool ok = beat.empty() && close.empty();
        p1 = p1 && ok;
        md << "- " << s << " (" << def->triangles << " triangles, default = " << def->variant << ", "
           << fmt("%.2g", def->worstVolumePct) << " % / " << fmt("%.2g", def->worstCobPct) << " %, "
           << fmt("%.0f", def->meanNs) << " ns): " << (ok ? "holds" : "FAILS");
        for (const auto& b : beat) md << "; as accurate and faster: " << b;
        for (const auto& b : close) md << "; as accurate and less than 2× slower (high-poly rule): " << b;
        md << '\n';
    }
    md << "\nNothing as accurate and faster, overall: " << (p1 ? "holds" : "does not hold") << "\n";

    md << "\n## At ≤ 0.1 % volume error, cost ≤ 1/200 of texel-centre 1024²\n\n";
    bool p2 = true;
    int p2Shapes = 0;
    for (const auto& s : shapes) {
        const ConfigStats* tc = find(s, "texel-centre", 1024);
        const ConfigStats* def = find(s, "default", -1);
        if (!tc || !def) continue;
        const ConfigStats* cheapest = nullptr;
        for (const auto& c : all)
            if (c.shape == s && c.worstVolumePct <= 0.1 && (!cheapest || c.meanNs < cheapest->meanNs)) cheapest = &c;
        const double defRatio = def->meanNs / tc->meanNs;
        const bool ok = def->worstVolumePct <= 0.1 && defRatio <= 1.0 / 200;
        p2 = p2 && ok;
        ++p2Shapes;
        md << "- " << s << ": texel-centre 1024 " << fmt("%.0f", tc->meanNs) << " ns (" << fmt("%.2g", tc->worstVolumePct)
           << " % volume); default " << fmt("%.0f", def->meanNs) << " ns = 1/" << fmt("%.0f", 1.0 / defRatio)
           << " at " << fmt("%.2g", def->worstVolumePct) << " % → " << (ok ? "holds" : "FAILS");
        if (cheapest)
            md << "; cheapest at ≤ 0.1 %: " << label(*cheapest) << " " << fmt("%.0f", cheapest->meanNs) << " ns = 1/"
               << fmt("%.0f", tc->meanNs / cheapest->meanNs);
        md << '\n';
    }
    if (p2Shapes == 0) md << "Not measured in this run (needs texel-centre 1024; `buoyancy bench` without --quick).\n";
    else md << "\nCost ≤ 1/200 of texel-centre 1024², overall: " << (p2 ? "holds" : "does not hold") << "\n";

    md << wavesMarkdown(everything);

    md << "\n## 1,000 bodies in real time on 2 cores\n\n";
    const ScalingRow* p3 = nullptr;
    for (const auto& r : scaling)
        if (r.bodies == 1000 && r.threads == 2 && r.variant.empty() && r.driver == "world") p3 = &r;
    if (!p3) {
        md << "Not measured in this run (needs 1,000 bodies and 2 threads; `buoyancy bench` without --quick).\n";
    } else {
        md << "- " << p3->model << " (" << p3->triangles << " triangles, default = " << p3->method << "), "
           << p3->bodies << " bodies, 2 threads: " << fmt("%.3f", p3->wallSeconds) << " s wall for "
           << fmt("%.3f", p3->simSeconds) << " s simulated → real-time factor " << fmt("%.3f", p3->realtimeFactor)
           << " (" << fmt("%.0f", p3->nsPerBodySubstepTotal) << " ns per body-substep, of which buoyancy "
           << fmt("%.0f", p3->nsPerBodySubstepBuoyancy) << ") → "
           << (p3->realtimeFactor >= 1 ? "holds with a margin of " + fmt("%.2f", p3->realtimeFactor) + "×."
                                       : "FAILS; needs " + fmt("%.1f", 1.0 / p3->realtimeFactor) + "× less work to hold.")
           << "\n";
        // What fits in real time today (the cost per body is flat in the body count: scaling.csv), and what the second
        // thread gave at the same body count.
        md << "- In real time on 2 cores at these settings: about " << fmt("%.0f", std::floor(p3->bodies * p3->realtimeFactor))
           << " bodies of this model (bodies × real-time factor).\n";
        for (const auto& one : scaling)
            if (one.bodies == p3->bodies && one.threads == 1 && one.variant.empty() && one.driver == "world")
                md << "- 2 threads against 1 at " << one.bodies << " bodies: buoyancy "
                   << fmt("%.2f", one.nsPerBodySubstepBuoyancy / p3->nsPerBodySubstepBuoyancy) << "× faster, whole step "
                   << fmt("%.2f", one.nsPerBodySubstepTotal / p3->nsPerBodySubstepTotal) << "× (Bullet's own step stays on one thread).\n";
    }
    // Through the public API (driver `world`): the largest fleet in real time (median of the timed windows), the cost
    // per body-substep against the body count, where the time goes, and the benchmark's own driver beside it.
    const ScalingRow* best = nullptr;
    for (const auto& r : scaling)
        if (r.driver == "world" && r.threads == 2 && r.variant.empty() && r.bodies >= 100 && r.realtimeFactor >= 1 &&
            (!best || r.bodies > best->bodies))
            best = &r;
    if (best)
        md << "- Through the public API (one btBuoyancyAction per body in the Bullet world, stepSimulation, 2 threads): "
           << best->bodies << " boats in real time (median real-time factor " << fmt("%.3f", best->realtimeFactor)
           << " over " << best->windows << " timed seconds, lowest " << fmt("%.3f", best->realtimeFactorMin) << ").\n";
    for (int threads : {1, 2}) {
        std::string line;
        for (const auto& r : scaling)
            if (r.driver == "world" && r.threads == threads && r.variant.empty() && r.bodies >= 100)
                line += (line.empty() ? "" : ", ") + std::to_string(r.bodies) + ": " + fmt("%.0f", r.nsPerBodySubstepTotal) +
                        " (buoyancy " + fmt("%.0f", r.nsPerBodySubstepBuoyancy) + ", Bullet " +
                        fmt("%.0f", r.nsPerBodySubstepTotal - r.nsPerBodySubstepBuoyancy) + ")";
        if (!line.empty())
            md << "- ns per body-substep, " << threads << " thread(s), bodies: " << line << ".\n";
    }
    for (const auto& b : scaling) {
        if (b.driver != "bench" || !b.variant.empty()) continue;
        for (const auto& w : scaling)
            if (w.driver == "world" && w.variant.empty() && w.bodies == b.bodies && w.threads == b.threads)
                md << "- " << b.bodies << " boats, " << b.threads << " thread(s): the library's threads "
                   << fmt("%.0f", w.nsPerBodySubstepTotal) << " ns per body-substep (real-time factor "
                   << fmt("%.3f", w.realtimeFactor) << "), the benchmark's own OpenMP driver "
                   << fmt("%.0f", b.nsPerBodySubstepTotal) << " (" << fmt("%.3f", b.realtimeFactor) << ").\n";
    }
    // The 1,000-body run with a longer temporal level of detail (hydrostaticsInterval K; its force error: temporal_lod.csv below).
    for (const auto& r : scaling)
        if (r.bodies >= 1000 && r.threads == 2 && r.variant.rfind("interval ", 0) == 0)
            md << "- With hydrostaticsInterval " << r.variant.substr(9)
               << " (exact every K-th substep, predicted in between): " << fmt("%.0f", r.nsPerBodySubstepTotal)
               << " ns per body-substep on 2 threads, real-time factor " << fmt("%.3f", r.realtimeFactor) << " → "
               << (r.realtimeFactor >= 1 ? "real time" : "not real time") << ".\n";
    // Level of detail on/off in the same run (design.md 2.5): the "no-lod" rows use dragClusters = 0 and
    // waterPatchNodes = 0 (every fine drag sample, one exact wave query per vertex/sample), the previous default.
    for (const auto& off : scaling) {
        if (off.variant != "no-lod") continue;
        for (const auto& on : scaling)
            if (on.variant.empty() && on.bodies == off.bodies && on.threads == off.threads)
                md << "- Level of detail, " << on.bodies << " bodies, " << on.threads << " thread(s): "
                   << fmt("%.0f", off.nsPerBodySubstepBuoyancy) << " ns buoyancy per body-substep without (no-lod) → "
                   << fmt("%.0f", on.nsPerBodySubstepBuoyancy) << " ns with the default level of detail ("
                   << fmt("%.1f", off.nsPerBodySubstepBuoyancy / on.nsPerBodySubstepBuoyancy) << "× faster).\n";
    }
    return md.str();
}

}  // namespace buoyancy::bench
