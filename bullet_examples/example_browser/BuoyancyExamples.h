#pragma once
/// @file BuoyancyExamples.h
/// Our example scenes as examples of Bullet's ExampleBrowser (examples/ExampleBrowser in Bullet's source tree):
/// one create function per scene, in the shape Bullet's ExampleEntry wants
/// (`CommonExampleInterface* (CommonExampleOptions&)`), and the rows of the "Buoyancy" group
/// (BuoyancyExampleEntries.inc). Each returns a BuoyancyBulletExample around the scene of the same name in
/// bullet_examples/example_scenes/ExampleEntries.h: the same scene files, world builder and fixed step as
/// `buoyancy run` and `buoyancy_browser`. Built by scripts/example-browser.sh (docs/example-browser.md).

class CommonExampleInterface;
struct CommonExampleOptions;

/// The description of our scene row `name` (bullet_examples/example_scenes/ExampleEntries.cpp), "" when unknown:
/// the ExampleBrowser shows it under the example.
const char* BuoyancyExampleDescription(const char* name);

///@name Create functions, one per scene (the scene file in brackets)
CommonExampleInterface* BuoyancyBuoyInWavesCreateFunc(CommonExampleOptions& options);         ///< buoy_waves.json
CommonExampleInterface* BuoyancyBoatHoledBowCreateFunc(CommonExampleOptions& options);        ///< boat_holed_bow.json
CommonExampleInterface* BuoyancyBoatHoledSternCreateFunc(CommonExampleOptions& options);      ///< boat_holed_stern.json
CommonExampleInterface* BuoyancyBallStabilityCreateFunc(CommonExampleOptions& options);       ///< ball_stability.json
CommonExampleInterface* BuoyancyVariableDensityBallCreateFunc(CommonExampleOptions& options); ///< variable_density_ball.json
CommonExampleInterface* BuoyancyPlushToyCreateFunc(CommonExampleOptions& options);            ///< plush_toy.json
CommonExampleInterface* BuoyancyBalloonCreateFunc(CommonExampleOptions& options);             ///< balloon_air.json
CommonExampleInterface* BuoyancyFftFleetCreateFunc(CommonExampleOptions& options);            ///< fft_fleet.json
CommonExampleInterface* BuoyancyBeachBoatCreateFunc(CommonExampleOptions& options);           ///< beach_boat.json
CommonExampleInterface* BuoyancyCrateSplashCreateFunc(CommonExampleOptions& options);         ///< crate_splash.json
CommonExampleInterface* BuoyancyGerstnerDemoCreateFunc(CommonExampleOptions& options);        ///< demo_boat_gerstner.json
///@}
