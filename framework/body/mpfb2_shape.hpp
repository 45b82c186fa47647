#pragma once
// MPFB2 / MakeHuman macro shape: the parameters that stand in for SMPL's beta (seed 000 §3.1, Eq. 2:
// T(beta) = T + B_s(beta)), and the blend of macro targets they select.
//
// Each macro variable x in [0, 1] falls in one part of its range (macro.json, nominal ends 0, 0.5,
// 1): with t = (x - lower end) / (upper end - lower end) the part's `low` target gets weight 1 - t and
// its `high` target t (an empty name means "no target"). E.g. muscle 0.75 = averagemuscle 0.5 +
// maxmuscle 0.5; height 0.25 = minheight 0.5; gender 0.3 = female 0.7 + male 0.3.
// Combined targets multiply their variables' weights (macro.json "combinations"):
//   universal-<gender>-<age>-<muscle>-<weight>                      (genderagemuscleweight)
//   <race>-<gender>-<age>                                           (racegenderage)
//   height/<gender>-<age>-<muscle>-<weight>-<min|max>height          (…height)
//   proportions/<gender>-<age>-<muscle>-<weight>-<uncommon|ideal>proportions
// Race weights are the three ethnic shares, normalised to sum 1 (MakeHuman's default: 1/3 each).
// Only adult targets ship with the test assets, so age must be in [0.5, 1] (0.5 = 25 years,
// 1 = 90 years in MakeHuman's age mapping); younger ages are rejected.
#include <string>
#include <utility>
#include <vector>

#include "framework/body/mpfb2_model.hpp"

namespace crowdlab {

struct Mpfb2ShapeParams {
  double gender = 0.5;       ///< 0 female .. 1 male
  double age = 0.5;          ///< 0.5 (25 y) .. 1 (90 y)
  double muscle = 0.5;       ///< 0 min .. 0.5 average .. 1 max
  double weight = 0.5;       ///< 0 min .. 0.5 average .. 1 max
  double height = 0.5;       ///< 0 min .. 0.5 average .. 1 max
  double proportions = 0.5;  ///< 0 uncommon .. 0.5 neutral .. 1 ideal
  double african = 1.0 / 3.0;
  double asian = 1.0 / 3.0;
  double caucasian = 1.0 / 3.0;
};

/// Checks ranges; throws InputError naming the parameter.
void validate_shape_params(const Mpfb2ShapeParams& p);

/// The targets (names for Mpfb2Model::target) and their weights; zero weights are left out; sorted
/// by name so that summation order (and hence the result) is reproducible.
std::vector<std::pair<std::string, double>> macro_target_weights(const Mpfb2Model& model,
                                                                 const Mpfb2ShapeParams& p);

/// Every base-mesh vertex after the macro targets (decimetres, OBJ frame).
std::vector<Vec3> shaped_vertices_dm(const Mpfb2Model& model, const Mpfb2ShapeParams& p);

}  // namespace crowdlab
