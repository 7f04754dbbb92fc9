// talus/talus.h: the whole public API in one include, so that an application
// writes one line before its first step:
//
//   #include <talus/talus.h>
//
//   talus::World world;
//   world.CreateBody({.type = talus::BodyType::Dynamic, ...});
//   world.Step(1.0 / 60.0);
//
// Each header it pulls in documents its own items (units, defaults, ranges);
// including a single one of them is as good when a file needs only that.
// hull_build_trace.h is included too: it is a public feature (a record of
// every Quickhull iteration, for figures and teaching), opt-in through
// HullBuildSettings::trace and free when not requested.
#pragma once

#include "talus/body.h"
#include "talus/broad_phase.h"
#include "talus/contact_query.h"
#include "talus/hull.h"
#include "talus/hull_build_trace.h"
#include "talus/hull_builder.h"
#include "talus/hull_queries.h"
#include "talus/mass_properties.h"
#include "talus/math.h"
#include "talus/narrow_phase.h"
#include "talus/pair_query.h"
#include "talus/result.h"
#include "talus/shape.h"
#include "talus/step_stage.h"
#include "talus/step_statistics.h"
#include "talus/transform.h"
#include "talus/world.h"
#include "talus/world_settings.h"
