#!/usr/bin/env Rscript
# Reference emmeans post-hocs for tests/analysis/ (issue 20): pairwise comparisons after afex::aov_ez on
# Maxwell & Delaney's md_12.1 (tests/data/analysis/md_12.1.csv), for a main effect and the interaction
# cells, with the univariate model (error strata pooled, Satterthwaite df: crowdlab's --error pooled)
# and the multivariate model (each contrast's own error: --error separate); Tukey-adjusted p (emmeans'
# default for pairs) and Bonferroni.
# Run from the repository root:   Rscript scripts/make_reference_emmeans.R [OUT_DIR]
# Needs Debian's r-base-core, r-cran-afex and r-cran-emmeans. Outputs: ref_emmeans_md_12.1.csv and
# ref_emmeans_mixed_sim.csv (a design with a between factor: `posthoc --between`).
suppressMessages({library(afex); library(emmeans)})
args <- commandArgs(trailingOnly = TRUE)
out <- if (length(args) > 0) args[1] else "tests/data/analysis"
source("scripts/reference_helpers.R")
# emmeans_rows: every (model, effect spec, adjustment) of pairs(emmeans(fit, spec, model = model)); cell
# labels joined with ':' ("lab:low"), a contrast "a|b".
emmeans_rows <- function(a, specs) {
  rows <- NULL
  for (model in c("univariate", "multivariate")) for (spec in specs) {
    fs <- strsplit(spec, ":")[[1]]
    em <- emmeans(a, fs, model = model)
    for (adj in c("tukey", "bonferroni")) {
      pr <- as.data.frame(summary(pairs(em), adjust = adj))
      unadj <- as.data.frame(summary(pairs(em), adjust = "none"))
      rows <- rbind(rows, data.frame(model = model, effect = spec, adjust = adj,
                                     contrast = gsub("X([0-9])", "\\1", gsub(" ", ":", gsub(" - ", "|", pr$contrast))),
                                     estimate = pr$estimate, se = pr$SE, df = pr$df, t = pr$t.ratio,
                                     p = unadj$p.value, p_adjusted = pr$p.value))
    }
  }
  rows
}
d <- read.csv(file.path(out, "md_12.1.csv"), colClasses = "character")
d$rt <- as.numeric(d$rt)
a <- aov_ez("id", "rt", d, within = c("angle", "noise"), include_aov = TRUE)
write_table(emmeans_rows(a, c("angle", "angle:noise")), "ref_emmeans_md_12.1.csv")
# A mixed design (issue 20, `posthoc --between`): mixed_sim.csv (scripts/make_reference_mixed_anova.R;
# lab 7 vs online 11 subjects, within density x method): the between factor, a within factor, and cells
# of between x within, the between factor first as afex names effects (and crowdlab labels cells).
m <- read.csv(file.path(out, "mixed_sim.csv"), colClasses = "character")
m$score <- as.numeric(m$score)
am <- suppressMessages(aov_ez("id", "score", m, between = "group", within = c("density", "method"),
                              include_aov = TRUE, fun_aggregate = mean))
write_table(emmeans_rows(am, c("group", "density", "group:density", "group:method", "group:density:method")),
            "ref_emmeans_mixed_sim.csv")
cat("wrote emmeans references to", out, "\n")
