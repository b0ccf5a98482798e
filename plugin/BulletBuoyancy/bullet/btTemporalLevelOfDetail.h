#pragma once
/// @file btTemporalLevelOfDetail.h
/// The Bullet layer's names of the temporal level of detail, kept for existing code: the controller lives in the
/// Bullet-free core, temporal/TemporalLevelOfDetail.h (design.md 2.5 "Fewer evaluations in time"). New code uses
/// buoyancy::TemporalLevelOfDetail, buoyancy::TemporalLevelOfDetailSettings and
/// buoyancy::TemporalLevelOfDetailSubstep. The records' names (btHydrostaticsHistory, btHydrostaticsSnapshot) come with
/// this header, as before.

#include <BulletBuoyancy/bullet/btHydrostaticsHistory.h>
#include <BulletBuoyancy/temporal/TemporalLevelOfDetail.h>

/// buoyancy::TemporalLevelOfDetailSettings: what the temporal level of detail is asked for at a substep.
using btTemporalLevelOfDetailSettings = buoyancy::TemporalLevelOfDetailSettings;
/// buoyancy::TemporalLevelOfDetailSubstep: the substep a prediction or a record is made at, and the water.
using btTemporalLevelOfDetailSubstep = buoyancy::TemporalLevelOfDetailSubstep;
/// buoyancy::TemporalLevelOfDetail: the temporal level-of-detail controller of one body.
using btTemporalLevelOfDetail = buoyancy::TemporalLevelOfDetail;
