#pragma once
// study.html: what a researcher reads of a study. Its title says what the study varies and on which scenario; then
// the study's facts (its id, version, sweeps, variants, seeds), each key metric plotted against each swept key
// (study_plots.h: categories as categories, drift on log-log axes with an N^-1/2 guide, the run report's bands), and
// at the end the numbers: per metric, one row per grid point with the mean, the standard deviation and the number of
// seeds with a value. Self-contained (inline SVG, no script), deterministic, every text escaped.

#include <string>

#include "study_record.h"

namespace swa::study {

// "Formation, drift, safety and consistency against uav_count and agent.formation.neighbourhood — scenario
// study_drift_vs_n": the swept keys (the variants by their names) and the scenario file's name without its
// directory and .yaml.
std::string studyTitle(const StudyRecord& study);

std::string studyHtml(const StudyRecord& study);

}  // namespace swa::study
