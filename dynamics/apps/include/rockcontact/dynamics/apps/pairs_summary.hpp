#pragma once
// The human-readable summary of a `rockcontact pairs` run: a table with one row per pair (id,
// status, IP area, |force| and its components, contact point, exact fallbacks; in 3D volume,
// distance, penetration depth, contact-set dimension, constraint count and largest penalty
// force; an error row shows the message instead), then totals: pairs by status, predicates, fallbacks and fallback
// rate, wall time and time per pair. Reads the output document of run_pairs (pairs_io.hpp).

#include <nlohmann/json.hpp>
#include <ostream>

namespace rockcontact::dynamics {

void write_pairs_summary(std::ostream& out, const nlohmann::ordered_json& document);

}  // namespace rockcontact::dynamics
