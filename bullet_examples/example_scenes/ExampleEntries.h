#pragma once
/// @file ExampleEntries.h
/// The table of example scenes (Bullet: examples/ExampleBrowser/ExampleEntries.cpp) and one create function
/// per scene (Bullet: the `...CreateFunc` each example exports).

#include "example_scenes/ExampleInterface.h"

#include <string>

namespace buoyancy::examples {

/// Number of rows of the table (headings included).
int exampleEntryCount();
/// Row i (0 ≤ i < exampleEntryCount()).
const ExampleEntry& exampleEntry(int i);
/// The row whose name is `name` (case-sensitive), or null.
const ExampleEntry* findExampleEntry(const char* name);
/// Number of scenes (rows with a create function; headings not counted).
int exampleSceneCount();
/// The row of the scene named `nameOrNumber`, or of scene number k (1 ≤ k ≤ exampleSceneCount(), in table
/// order, as `buoyancy_browser --list` numbers them). @return the row, or -1 with `error` saying why (a heading,
/// a number out of range, an unknown name) and giving the valid range
int findExampleScene(const std::string& nameOrNumber, std::string& error);

///@name Create functions, one per scene (paper figure in brackets)
ExampleScene* BuoyInWavesCreateFunc(ExampleOptions& options);       ///< buoy_waves.json (Figs. 10–11)
ExampleScene* BoatHoledBowCreateFunc(ExampleOptions& options);      ///< boat_holed_bow.json (Fig. 12)
ExampleScene* BoatHoledSternCreateFunc(ExampleOptions& options);    ///< boat_holed_stern.json (Fig. 13)
ExampleScene* BallStabilityCreateFunc(ExampleOptions& options);     ///< ball_stability.json (Fig. 14)
ExampleScene* VariableDensityBallCreateFunc(ExampleOptions& options); ///< variable_density_ball.json (Fig. 15)
ExampleScene* PlushToyCreateFunc(ExampleOptions& options);          ///< plush_toy.json (Fig. 16)
ExampleScene* BalloonCreateFunc(ExampleOptions& options);           ///< balloon_air.json + BalloonExample (Fig. 17)
ExampleScene* FftFleetCreateFunc(ExampleOptions& options);          ///< fft_fleet.json
ExampleScene* BeachBoatCreateFunc(ExampleOptions& options);         ///< beach_boat.json
ExampleScene* CrateSplashCreateFunc(ExampleOptions& options);       ///< crate_splash.json
ExampleScene* GerstnerDemoCreateFunc(ExampleOptions& options);      ///< demo_boat_gerstner.json
///@}

}  // namespace buoyancy::examples
