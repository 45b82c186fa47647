#!/usr/bin/env Rscript
# Reference linear mixed models for tests/analysis/ (issue 20), fitted by lme4::lmer.
# Run from the repository root:   Rscript scripts/make_reference_lmm.R [OUT_DIR]
# Needs Debian's r-base-core, r-cran-lme4 and r-cran-lmertest. crowdlab never depends on R: the outputs are committed.
# lmer runs with a tight optimiser (minqa's BOBYQA, rhoend = 1e-12) so that the reference is the
# optimum itself, not lme4's default stopping point (nloptwrap's defaults stop ~1e-8 short in deviance,
# which moves the SEs by ~1e-5).
# Inputs written here: lmm_sim.csv (30 participants, 24 stimuli, method baseline/ours, centred density,
#   2 repetitions; a correlated random intercept and method slope, and a stimulus intercept) and
#   lmm_flat.csv (a random slope with no variance: lme4's singular fit).
# Outputs: ref_lmm.csv: one row per (model, quantity, name): fixed estimate/se/t, random sd/corr,
#   residual_sd, criterion (REMLcrit or deviance), singular, and lmerTest's Satterthwaite df and p of
#   each fixed term (lmerTest::as_lmerModLmerTest on the same fit: numDeriv's Richardson Hessian of the
#   deviance in (theta, sigma) and Jacobian of vcov(beta)).
suppressMessages(library(lme4))
args <- commandArgs(trailingOnly = TRUE)
out <- if (length(args) > 0) args[1] else "tests/data/analysis"
source("scripts/reference_helpers.R")

set.seed(4242)
np <- 30; ns <- 24
d <- expand.grid(rep = 1:2, method = c("baseline", "ours"), stimulus = 1:ns, participant = 1:np)
d$dens_c <- round(((d$stimulus - 1) %% 4) * 1.11 - 1.665, 3)
u <- MASS::mvrnorm(np, c(0, 0), matrix(c(0.5, 0.15, 0.15, 0.2), 2))
s <- rnorm(ns, 0, 0.3)
d$score <- round(3.2 + u[d$participant, 1] + s[d$stimulus] - 0.3 * d$dens_c +
                 (d$method == "ours") * (0.9 + u[d$participant, 2] + 0.15 * d$dens_c) + rnorm(nrow(d), 0, 0.7), 3)
d$participant <- paste0("p", d$participant); d$stimulus <- paste0("s", d$stimulus)
write.csv(d[, c("participant", "stimulus", "method", "dens_c", "rep", "score")], file.path(out, "lmm_sim.csv"),
          row.names = FALSE, quote = FALSE)

f <- expand.grid(rep = 1:3, cond = c("a", "b"), participant = 1:15)
f$participant <- paste0("q", f$participant)
b0 <- rnorm(15, 0, 0.8)
f$y <- round(1 + b0[as.integer(sub("q", "", f$participant))] + 0.5 * (f$cond == "b") + rnorm(nrow(f), 0, 1), 3)
write.csv(f[, c("participant", "cond", "rep", "y")], file.path(out, "lmm_flat.csv"), row.names = FALSE, quote = FALSE)

ctrl <- lmerControl(optimizer = "bobyqa", optCtrl = list(rhoend = 1e-12, maxfun = 1e5), calc.derivs = FALSE)
models <- list(
  list(name = "slope_reml", data = "lmm_sim.csv", formula = "score ~ dens_c * method + (1 + method | participant)", reml = TRUE),
  list(name = "slope_ml", data = "lmm_sim.csv", formula = "score ~ dens_c * method + (1 + method | participant)", reml = FALSE),
  list(name = "crossed_reml", data = "lmm_sim.csv", formula = "score ~ dens_c + method + (1 | participant) + (1 | stimulus)", reml = TRUE),
  list(name = "intercept_ml", data = "lmm_sim.csv", formula = "score ~ method + (1 | participant)", reml = FALSE),
  list(name = "singular_reml", data = "lmm_flat.csv", formula = "y ~ cond + (1 + cond | participant)", reml = TRUE))
rows <- NULL
add <- function(model, quantity, name, value) rows <<- rbind(rows, data.frame(model = model, quantity = quantity, name = name, value = fmt(value)))
for (m in models) {
  dd <- read.csv(file.path(out, m$data))
  fit <- suppressMessages(lmer(as.formula(m$formula), data = dd, REML = m$reml, control = ctrl))
  cf <- summary(fit)$coefficients
  for (t in rownames(cf)) {
    add(m$name, "estimate", t, cf[t, "Estimate"]); add(m$name, "se", t, cf[t, "Std. Error"]); add(m$name, "t", t, cf[t, "t value"])
  }
  vc <- as.data.frame(VarCorr(fit))
  for (i in seq_len(nrow(vc))) {
    if (vc$grp[i] == "Residual") { add(m$name, "residual_sd", "", vc$sdcor[i]); next }
    if (is.na(vc$var2[i])) add(m$name, "sd", paste(vc$grp[i], vc$var1[i], sep = "/"), vc$sdcor[i])
    else add(m$name, "corr", paste(vc$grp[i], vc$var1[i], vc$var2[i], sep = "/"), vc$sdcor[i])
  }
  add(m$name, "criterion", if (m$reml) "REML" else "deviance", if (m$reml) REMLcrit(fit) else deviance(fit))
  add(m$name, "singular", "", as.numeric(isSingular(fit)))
  satt <- suppressWarnings(summary(lmerTest::as_lmerModLmerTest(fit))$coefficients)
  for (t in rownames(satt)) { add(m$name, "df", t, satt[t, "df"]); add(m$name, "p", t, satt[t, "Pr(>|t|)"]) }
}
write.csv(rows, file.path(out, "ref_lmm.csv"), row.names = FALSE, quote = FALSE)
models_tab <- do.call(rbind, lapply(models, function(m) data.frame(model = m$name, data = m$data, formula = m$formula, reml = m$reml)))
write.csv(models_tab, file.path(out, "ref_lmm_models.csv"), row.names = FALSE, quote = TRUE)
cat("wrote LMM references to", out, "\n")
