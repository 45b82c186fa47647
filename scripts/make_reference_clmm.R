#!/usr/bin/env Rscript
# Reference cumulative link mixed models for tests/analysis/ (issue 20), fitted by ordinal::clmm
# (Laplace approximation, random intercepts). Run from the repository root:
#   Rscript scripts/make_reference_clmm.R [OUT_DIR]
# Needs Debian's r-base-core and r-cran-ordinal. Inputs written here: likert_sim.csv (30 participants,
# method baseline/ours x density low/mid/high, 3 repetitions, a 5-point rating). Output: ref_clmm.csv
# (model, quantity, name, value): thresholds, fixed effects (estimate, se), random sd, logLik.
suppressMessages(library(ordinal))
args <- commandArgs(trailingOnly = TRUE)
out <- if (length(args) > 0) args[1] else "tests/data/analysis"
source("scripts/reference_helpers.R")
set.seed(555)
d <- expand.grid(rep = 1:3, density = c("low", "mid", "high"), method = c("baseline", "ours"), participant = 1:30)
b <- rnorm(30, 0, 0.9)
eta <- b[d$participant] + 1.1 * (d$method == "ours") - 0.5 * (d$density == "high") + 0.3 * (d$density == "mid") +
       0.4 * (d$method == "ours") * (d$density == "high")
cut <- c(-1.5, -0.4, 0.6, 1.7)
d$rating <- sapply(eta + rlogis(nrow(d)), function(v) 1 + sum(v > cut))
d$participant <- paste0("p", d$participant)
write.csv(d[, c("participant", "method", "density", "rep", "rating")], file.path(out, "likert_sim.csv"),
          row.names = FALSE, quote = FALSE)
models <- list(list(name = "logit", formula = "rating ~ method * density + (1 | participant)", link = "logit"),
               list(name = "probit", formula = "rating ~ method + density + (1 | participant)", link = "probit"))
rows <- NULL
add <- function(model, quantity, name, value) rows <<- rbind(rows, data.frame(model = model, quantity = quantity, name = name, value = fmt(value)))
for (m in models) {
  dd <- read.csv(file.path(out, "likert_sim.csv"))
  dd$rating <- factor(dd$rating, ordered = TRUE)
  fit <- clmm(as.formula(m$formula), data = dd, link = m$link, Hess = TRUE,
              control = clmm.control(method = "nlminb", gradTol = 1e-10, innerCtrl = "noWarn",
                                     rel.tol = 1e-14, x.tol = 1e-12, eval.max = 5000, iter.max = 5000))
  co <- summary(fit)$coefficients
  for (t in names(fit$alpha)) { add(m$name, "threshold", t, co[t, "Estimate"]); add(m$name, "threshold_se", t, co[t, "Std. Error"]) }
  for (t in names(fit$beta)) { add(m$name, "estimate", t, co[t, "Estimate"]); add(m$name, "se", t, co[t, "Std. Error"]) }
  add(m$name, "sd", "participant", attr(VarCorr(fit)$participant, "stddev"))
  add(m$name, "loglik", "", as.numeric(logLik(fit)))
}
write_table(rows, "ref_clmm.csv")
cat("wrote CLMM references to", out, "\n")
