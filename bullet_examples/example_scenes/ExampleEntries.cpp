#include "example_scenes/ExampleEntries.h"

#include "example_scenes/BalloonExample.h"
#include "example_scenes/SceneFileExample.h"

#include <cstring>

namespace buoyancy::examples {

ExampleScene* BuoyInWavesCreateFunc(ExampleOptions& o) { return new SceneFileExample(o, "buoy_waves.json"); }
ExampleScene* BoatHoledBowCreateFunc(ExampleOptions& o) { return new SceneFileExample(o, "boat_holed_bow.json"); }
ExampleScene* BoatHoledSternCreateFunc(ExampleOptions& o) { return new SceneFileExample(o, "boat_holed_stern.json"); }
ExampleScene* BallStabilityCreateFunc(ExampleOptions& o) { return new SceneFileExample(o, "ball_stability.json"); }
ExampleScene* VariableDensityBallCreateFunc(ExampleOptions& o) {
    return new SceneFileExample(o, "variable_density_ball.json");
}
ExampleScene* PlushToyCreateFunc(ExampleOptions& o) { return new SceneFileExample(o, "plush_toy.json"); }
ExampleScene* BalloonCreateFunc(ExampleOptions& o) { return new BalloonExample(o); }
ExampleScene* FftFleetCreateFunc(ExampleOptions& o) { return new SceneFileExample(o, "fft_fleet.json"); }
ExampleScene* BeachBoatCreateFunc(ExampleOptions& o) { return new SceneFileExample(o, "beach_boat.json"); }
ExampleScene* CrateSplashCreateFunc(ExampleOptions& o) { return new SceneFileExample(o, "crate_splash.json"); }
ExampleScene* GerstnerDemoCreateFunc(ExampleOptions& o) { return new SceneFileExample(o, "demo_boat_gerstner.json"); }
ExampleScene* ZUpPlankCreateFunc(ExampleOptions& o) { return new SceneFileExample(o, "zup_plank.json"); }
ExampleScene* RiversAndLakesCreateFunc(ExampleOptions& o) { return new SceneFileExample(o, "rivers_and_lakes.json"); }

namespace {

const ExampleEntry kEntries[] = {
    {0, "Paper figures", "Scenes of Bajo, Patow & Delrieux, CGF 2020.", nullptr, 0},
    {1, "Buoy in waves", "Figs. 10-11: a buoy heaving in Gerstner waves; weight (red) and buoyancy (green) arrows.",
     BuoyInWavesCreateFunc, 0},
    {1, "Boat holed at the bow", "Fig. 12: water enters a hole at the bow and runs aft through the compartments; "
                                 "the boat sinks bow first.", BoatHoledBowCreateFunc, 0},
    {1, "Boat holed at the stern", "Fig. 13: the same boat holed at the stern sinks stern first.",
     BoatHoledSternCreateFunc, 0},
    {1, "Uniform vs bottom-heavy ball", "Fig. 14: two balls released tilted; the uniform one is neutral and keeps "
                                        "turning, the ballasted one rights itself.", BallStabilityCreateFunc, 0},
    {1, "Variable-density ball", "Fig. 15: a ball whose heavy spot moves over its surface rolls to follow it.",
     VariableDensityBallCreateFunc, 0},
    {1, "Plush toy soaking", "Fig. 16: a plush bear soaks up water through its fabric and settles lower.",
     PlushToyCreateFunc, 0},
    {1, "Balloon in air", "Fig. 17: a light deformable balloon rises in air (fluid density 1.2 kg/m3).",
     BalloonCreateFunc, 0},
    {0, "Beyond the paper", "Larger scenes.", nullptr, 0},
    {1, "FFT fleet", "200 mixed bodies (boxes, balls, logs, boats) in an FFT ocean.", FftFleetCreateFunc, 0},
    {1, "Boat onto a beach", "Waves push a boat up a sloped beach: contacts and buoyancy together.",
     BeachBoatCreateFunc, 0},
    {1, "Crate splash", "A crate dropped into the interactive water makes rings that rock a neighbour.",
     CrateSplashCreateFunc, 0},
    {1, "Gerstner demo", "The demo of scripts/demo.sh: a boat, a buoy, a crate and a log in Gerstner waves.",
     GerstnerDemoCreateFunc, 0},
    {1, "Z-up plank", "A robotics-style world with gravity along -z: a plank rides Gerstner waves whose frame is z-up; "
                      "the view follows the up axis.", ZUpPlankCreateFunc, 0},
    {1, "Rivers and lakes", "A pool and a lake at different levels and a river whose current carries a boat "
                            "downstream.", RiversAndLakesCreateFunc, 0},
};

}  // namespace

int exampleEntryCount() { return int(sizeof kEntries / sizeof kEntries[0]); }

const ExampleEntry& exampleEntry(int i) { return kEntries[i]; }

const ExampleEntry* findExampleEntry(const char* name) {
    for (const ExampleEntry& e : kEntries)
        if (std::strcmp(e.name, name) == 0) return &e;
    return nullptr;
}

int exampleSceneCount() {
    int n = 0;
    for (const ExampleEntry& e : kEntries) n += e.createFunc ? 1 : 0;
    return n;
}

int findExampleScene(const std::string& nameOrNumber, std::string& error) {
    const int scenes = exampleSceneCount();
    const std::string range = "1.." + std::to_string(scenes);
    const bool digits = !nameOrNumber.empty() && nameOrNumber.size() < 10 &&
                        nameOrNumber.find_first_not_of("0123456789") == std::string::npos;
    if (digits) {
        const int k = std::stoi(nameOrNumber);
        int seen = 0;
        for (int i = 0; i < exampleEntryCount(); ++i)
            if (kEntries[i].createFunc && ++seen == k) return i;
        error = "no scene number " + nameOrNumber + ": scenes are numbered " + range + " (buoyancy_browser --list)";
        return -1;
    }
    for (int i = 0; i < exampleEntryCount(); ++i) {
        if (nameOrNumber != kEntries[i].name) continue;
        if (kEntries[i].createFunc) return i;
        error = "\"" + nameOrNumber + "\" is a group heading, not a scene: give a scene's name or its number " + range +
                " (buoyancy_browser --list)";
        return -1;
    }
    error = "no scene \"" + nameOrNumber + "\": give a scene's name or its number " + range +
            " (buoyancy_browser --list)";
    return -1;
}

}  // namespace buoyancy::examples
