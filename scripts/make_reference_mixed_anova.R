#!/usr/bin/env Rscript
# Reference mixed (split-plot) and between-subjects ANOVAs for tests/analysis/ (issue 20).
# Run from the repository root:   Rscript scripts/make_reference_mixed_anova.R [OUT_DIR]
# Needs Debian's r-base-core and r-cran-afex. crowdlab never depends on R: the outputs are committed.
# Inputs written here (data only):
#   obk_long.csv    O'Brien & Kaiser (1985) data as shipped by afex (obk.long): between treatment (3) x
#                   gender (2), unequal cells (16 subjects); within phase (3) x hour (5)
#   mixed_sim.csv   simulated: between group lab/online (7 vs 11 subjects), within density (3) x
#                   method (2), 2 repetitions per cell (averaged)
# Outputs: ref_mixed_<name>.csv and ref_between_obk_long.csv (the between factors only, on each
#   subject's mean over all within cells), one row per effect in afex's order: afex::aov_ez(type = 3) /
#   car::Anova univariate tests (SS, error SS, df, F, p), afex's pes and ges, Mauchly's W and p, GG and
#   HF epsilons and corrected p (empty where they do not apply).
suppressMessages(library(afex))
args <- commandArgs(trailingOnly = TRUE)
out <- if (length(args) > 0) args[1] else "tests/data/analysis"
source("scripts/reference_helpers.R")

data(obk.long, package = "afex")
write.csv(obk.long[, c("id", "treatment", "gender", "phase", "hour", "value")], file.path(out, "obk_long.csv"),
          row.names = FALSE, quote = FALSE)

set.seed(2020)
sim <- expand.grid(rep = 1:2, method = c("baseline", "ours"), density = c("low", "mid", "high"), id = 1:18)
sim$group <- ifelse(sim$id <= 7, "lab", "online")
bias <- rnorm(18, 0, 0.6)
d_i <- as.integer(factor(sim$density, levels = c("low", "mid", "high"))) - 1
sim$score <- round(3 + bias[sim$id] + 0.4 * (sim$group == "online") - 0.3 * d_i +
                   ifelse(sim$method == "ours", 0.8 + 0.2 * d_i * (sim$group == "lab"), 0) +
                   rnorm(nrow(sim), 0, 0.5 + 0.3 * d_i), 2)
write.csv(sim[, c("id", "group", "density", "method", "rep", "score")], file.path(out, "mixed_sim.csv"),
          row.names = FALSE, quote = FALSE)

mixed_ref <- function(name, id, dv, between, within, file = paste0("ref_mixed_", name, ".csv")) {
  d <- read.csv(file.path(out, paste0(name, ".csv")), colClasses = "character")
  d[[dv]] <- as.numeric(d[[dv]])
  a <- aov_ez(id, dv, d, between = between, within = within, fun_aggregate = mean, type = 3,
              anova_table = list(correction = "none", es = c("pes", "ges")))
  tab <- a$anova_table
  s <- NULL  # between-only: no sphericity tests
  if (is.null(within)) {
    u <- a$Anova
    eff <- setdiff(rownames(u), c("(Intercept)", "Residuals"))
    res <- data.frame(effect = eff, df1 = u[eff, "Df"], df2 = u["Residuals", "Df"], SS = u[eff, "Sum Sq"],
                      SS_error = u["Residuals", "Sum Sq"], F = u[eff, "F value"], p = u[eff, "Pr(>F)"])
  } else {
    s <- suppressWarnings(summary(a$Anova, multivariate = FALSE))
    u <- s$univariate.tests
    eff <- setdiff(rownames(u), "(Intercept)")
    res <- data.frame(effect = eff, df1 = u[eff, "num Df"], df2 = u[eff, "den Df"], SS = u[eff, "Sum Sq"],
                      SS_error = u[eff, "Error SS"], F = u[eff, "F value"], p = u[eff, "Pr(>F)"])
  }
  res$pes <- tab[eff, "pes"]
  res$ges <- tab[eff, "ges"]
  res <- add_sphericity(res, s)
  write_table(res, file)
}
mixed_ref("obk_long", "id", "value", c("treatment", "gender"), c("phase", "hour"))
mixed_ref("mixed_sim", "id", "score", "group", c("density", "method"))
# Between-subjects only: the subjects' mean score over all cells, group alone and with a second,
# unbalanced between factor (the obk.long groups).
mixed_ref("obk_long", "id", "value", c("treatment", "gender"), NULL, "ref_between_obk_long.csv")
cat("wrote mixed-ANOVA references to", out, "\n")
