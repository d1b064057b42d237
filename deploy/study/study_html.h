#pragma once
// study.html: each key metric of a study plotted against each swept key: at every value of that key the mean over
// the seeds (solid) and mean ± standard deviation (thin, dashed), one line per combination of the other swept keys'
// values. A swept key whose values are all numbers is a numeric x axis; otherwise its values are placed at 0, 1, 2 ...
// in the order given and named under the plot. Self-contained (inline SVG, no script), deterministic.

#include <string>

#include "study_record.h"

namespace swa::study {

std::string studyHtml(const StudyRecord& study);

}  // namespace swa::study
