#pragma once
// A balanced within-subject design built from tidy (long) rows: one value per subject per cell, the
// mean over that cell's repetitions. This is the input of every repeated-measures analysis here.
// Optional between-subject factors (a lab and an online group) give each subject one level each; the
// groups may differ in size (mixed / split-plot designs, analysis/mixed_anova.hpp).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "framework/core/csv.hpp"

namespace crowdlab::analysis {

struct WithinFactor {
  std::string name;
  std::vector<std::string> levels;  ///< in order of first appearance in the input (stable, not sorted)
};

struct WithinDesign {
  std::string source;                 ///< the CSV the design came from (for messages)
  std::string dv;                     ///< the dependent-variable column (for messages)
  std::vector<WithinFactor> factors;  ///< in the order the user named them
  std::vector<WithinFactor> between;  ///< between-subject factors, in the order the user named them
  std::vector<std::string> subjects;  ///< in order of first appearance
  /// subjects x between factors: the level index of each subject's group (empty without between).
  std::vector<std::vector<size_t>> subject_groups;
  /// subjects x cells. Cells are ordered with the LAST factor varying fastest (row-major over levels).
  Eigen::MatrixXd cell_means;

  size_t cell_count() const { return static_cast<size_t>(cell_means.cols()); }
  /// Level index of each factor for cell `cell`.
  std::vector<size_t> cell_levels(size_t cell) const;
  /// "A=a1, B=b2" for messages and tables.
  std::string cell_label(size_t cell) const;
};

/// Bounds on the work a design may ask for, checked before anything is allocated for it. A factor is
/// within-subject, so every subject sees every level: hundreds of levels almost always mean a wrong
/// column (an id, a stimulus name or a continuous value). The cost of the ANOVA grows with the cube of
/// the number of cells (rm_anova solves a d x d problem per effect, d < cells); the defaults keep it
/// under a second or so. Documented in docs/analysis.md ("Limits"); `analyze --max-levels/--max-cells`.
struct DesignLimits {
  size_t max_levels = 100;  ///< levels per factor
  size_t max_cells = 1000;  ///< product of the factors' levels
};

/// Builds the design from a CSV: `dv` numeric, `subject` and every name in `within` and `between` are
/// labels. Repetitions of a cell are averaged (afex::aov_ez's fun_aggregate = mean). `within` may be
/// empty when `between` is not (a between-subjects ANOVA of the subjects' means).
/// Also throws for a subject whose rows name two levels of a between factor (file:line, column).
/// Throws InputError: missing column (names it), a non-numeric or non-finite dv (file:line and column),
/// a subject lacking a cell (names the subject and the cell), fewer than 2 subjects, a factor with
/// fewer than 2 levels, or a design past `limits` (names the column and the count). The subjects x cells
/// matrix is allocated only once the rows are known to fill it, so its size is bounded by the file's.
WithinDesign build_within_design(const CsvTable& table, const std::string& dv, const std::string& subject,
                                 const std::vector<std::string>& within, const DesignLimits& limits = {},
                                 const std::vector<std::string>& between = {});

}  // namespace crowdlab::analysis
