#!/usr/bin/env Rscript
# Reference statistics for crowdlab's analysis tests (tests/data/analysis/), computed with R.
# Run from the repository root:   Rscript scripts/make_reference_stats.R [OUT_DIR]
# Needs Debian's r-base-core and r-cran-afex (apt-get install r-base-core r-cran-afex). crowdlab itself
# never depends on R: the outputs of this script are committed so the tests run without it.
#
# Inputs (data only):
#   rm_anova2.csv   pingouin's rm_anova2 data set (Subject, Time, Metric, Performance)
#   ez_2x3x2.csv    the 2x3x2 table of statsmodels' test_anova_rm.py (from ezANOVA)
#   md_12.1.csv     Maxwell & Delaney (2004) Table 12.1, exported here from afex's md_12.1
# Outputs:
#   ref_anova_<name>.csv   afex::aov_ez / car::Anova univariate tests per effect
#   ref_qtukey.csv         qtukey / ptukey on a grid of (p, nmeans, df)
#   ref_ks.csv             one-sample Kolmogorov-Smirnov statistics and p values (exact and asymptotic)
#   psychometric_trials.csv, ref_psychometric_glm.csv   simulated 2AFC answers and glm(binomial) fits
suppressMessages(library(afex))
args <- commandArgs(trailingOnly = TRUE)
out <- if (length(args) > 0) args[1] else "tests/data/analysis"
source("scripts/reference_helpers.R")

# ---- Maxwell & Delaney 12.1 data, from afex ------------------------------------------------------
data(md_12.1, package = "afex")
write.csv(md_12.1[, c("id", "angle", "noise", "rt")], file.path(out, "md_12.1.csv"), row.names = FALSE,
          quote = FALSE)

# ---- A simulated 5 x 4 x 2 design (16 subjects, 2 repetitions per cell): effects with df1 up to 12,
# so Mauchly's second-order term and the epsilons are exercised beyond df1 = 2 ----------------------
set.seed(20000)
sim <- expand.grid(rep = 1:2, method = c("baseline", "ours"), viewpoint = c("V1", "V2", "V3", "V4"),
                   density = c("2.22", "3.33", "4.44", "5.55", "6.66"), participant = 1:16)
bias <- rnorm(16, 0, 0.5)
dens_i <- as.integer(factor(sim$density)) - 1
sim$score <- round(3.3 + bias[sim$participant] - 0.3 * dens_i + ifelse(sim$method == "ours", 1 + 0.25 * dens_i, 0) +
                   rnorm(nrow(sim), 0, 0.8 + 0.1 * dens_i), 2)
write.csv(sim[, c("participant", "density", "viewpoint", "method", "rep", "score")], file.path(out, "sim_5x4x2.csv"),
          row.names = FALSE, quote = FALSE)

# ---- RM-ANOVA references --------------------------------------------------------------------------
anova_ref <- function(name, id, dv, within) {
  d <- read.csv(file.path(out, paste0(name, ".csv")), colClasses = "character")
  d[[dv]] <- as.numeric(d[[dv]])
  for (w in c(id, within)) d[[w]] <- factor(d[[w]])
  a <- aov_ez(id, dv, d, within = within, fun_aggregate = mean,
              anova_table = list(correction = "none", es = c("pes", "ges")))
  s <- suppressWarnings(summary(a$Anova, multivariate = FALSE))
  u <- s$univariate.tests
  eff <- setdiff(rownames(u), "(Intercept)")
  res <- data.frame(effect = eff, df1 = u[eff, "num Df"], df2 = u[eff, "den Df"], SS = u[eff, "Sum Sq"],
                    SS_error = u[eff, "Error SS"], F = u[eff, "F value"], p = u[eff, "Pr(>F)"])
  res$MS <- res$SS / res$df1
  tab <- a$anova_table
  res$pes <- tab[eff, "pes"]
  res$ges <- tab[eff, "ges"]
  res <- add_sphericity(res, s)
  write_table(res, paste0("ref_anova_", name, ".csv"))
}
anova_ref("rm_anova2", "Subject", "Performance", c("Time", "Metric"))
anova_ref("ez_2x3x2", "id", "DV", c("A", "B", "D"))
anova_ref("md_12.1", "id", "rt", c("angle", "noise"))
anova_ref("sim_5x4x2", "participant", "score", c("density", "viewpoint", "method"))

# ---- Post-hoc references (md_12.1, effect angle and angle:noise) --------------------------------
d <- read.csv(file.path(out, "md_12.1.csv"), colClasses = "character")
d$rt <- as.numeric(d$rt)
a <- aov_ez("id", "rt", d, within = c("angle", "noise"), anova_table = list(correction = "none"))
n <- length(unique(d$id))
ph <- NULL
for (eff in c("angle", "angle:noise")) {
  fs <- strsplit(eff, ":")[[1]]
  key <- do.call(paste, c(d[fs], sep = ":"))
  m <- tapply(d$rt, list(d$id, key), mean)            # subjects x effect cells
  lv <- colnames(m)
  mse <- a$anova_table[eff, "MSE"]; df2 <- a$anova_table[eff, "den Df"]
  r <- nrow(d) / n / length(lv)                       # cells averaged per mean
  pairs <- combn(length(lv), 2)
  for (j in seq_len(ncol(pairs))) {
    i1 <- pairs[1, j]; i2 <- pairs[2, j]
    tt <- t.test(m[, i1], m[, i2], paired = TRUE)
    q <- abs(mean(m[, i1]) - mean(m[, i2])) / sqrt(mse / (n * r))
    ph <- rbind(ph, data.frame(effect = eff, level_a = lv[i1], level_b = lv[i2], t = unname(tt$statistic),
                               p_t = tt$p.value, p_bonferroni = min(1, tt$p.value * ncol(pairs)), q = q,
                               p_tukey = ptukey(q, length(lv), df2, lower.tail = FALSE)))
  }
}
write_table(ph, "ref_posthoc_md_12.1.csv")

# ---- Studentized range ----------------------------------------------------------------------------
grid <- expand.grid(p = c(0.5, 0.9, 0.95, 0.99), nmeans = c(2, 3, 5, 10, 20), df = c(2, 5, 10, 30, 120, Inf))
grid$q <- mapply(function(p, k, v) qtukey(p, k, v), grid$p, grid$nmeans, grid$df)
grid$ptukey_of_q <- mapply(function(q, k, v) ptukey(q, k, v), grid$q, grid$nmeans, grid$df)
# R documents qtukey as "accurate to the 4th decimal place", and its ptukey loses accuracy for small df
# (for 2 means, P(Q < q) = P(|T_df| < q / sqrt 2) shows it). For df < 10 the grid therefore also gets
# an independent quantile: the defining double integral evaluated with integrate() and inverted with
# uniroot() at tight tolerances.
ptukey_integral <- function(q, k, df) {
  W <- function(w) k * integrate(function(z) dnorm(z) * pmax(pnorm(z + w) - pnorm(z), 0)^(k - 1),
                                 -Inf, Inf, rel.tol = 1e-12)$value
  dens <- function(s) exp(log(2) + (df / 2) * log(df / 2) - lgamma(df / 2) + (df - 1) * log(s) - df * s^2 / 2)
  integrate(function(s) dens(s) * sapply(q * s, W), 0, Inf, rel.tol = 1e-11)$value
}
grid$q_integral <- mapply(function(p, k, v) {
  if (v >= 10) return(NA)
  uniroot(function(q) ptukey_integral(q, k, v) - p, c(0.01, 400), tol = 1e-12)$root
}, grid$p, grid$nmeans, grid$df)
write_table(grid, "ref_qtukey.csv")

# ---- Kolmogorov-Smirnov ---------------------------------------------------------------------------
set.seed(20260101)
ks <- NULL
for (n in c(5, 10, 20, 50, 99, 150, 400)) {
  x <- rnorm(n) * 1.1 + 0.2
  e <- suppressWarnings(ks.test(x, "pnorm", exact = (n < 100)))
  a <- suppressWarnings(ks.test(x, "pnorm", exact = FALSE))
  ks <- rbind(ks, data.frame(n = n, sample = paste(fmt(x), collapse = ";"), D = e$statistic,
                             p_exact_or_default = e$p.value, p_asymptotic = a$p.value))
}
write.csv(ks, file.path(out, "ref_ks.csv"), row.names = FALSE, quote = TRUE)

# ---- Psychometric: simulated 2AFC answers and glm(binomial) ------------------------------------
set.seed(7)
trials <- NULL
for (s in 1:6) for (sh in 0:2) {
  thr <- 0.35 + 0.05 * sh + rnorm(1, 0, 0.03)
  slope <- 25 + rnorm(1, 0, 4)
  for (dist in seq(0.2, 0.7, by = 0.05)) for (r in 1:8) {
    y <- rbinom(1, 1, plogis(-slope * (dist - thr)))
    trials <- rbind(trials, data.frame(participant = s, shoulder = sh, distance = round(dist, 2), rep = r,
                                       collision = y))
  }
}
write.csv(trials, file.path(out, "psychometric_trials.csv"), row.names = FALSE, quote = FALSE)
fits <- NULL
for (s in unique(trials$participant)) for (sh in unique(trials$shoulder)) {
  d <- trials[trials$participant == s & trials$shoulder == sh, ]
  g <- suppressWarnings(glm(collision ~ distance, family = binomial, data = d,
                            control = glm.control(epsilon = 1e-14, maxit = 100)))
  b <- coef(g)
  fits <- rbind(fits, data.frame(participant = s, shoulder = sh, intercept = b[1], slope = b[2],
                                 x50 = -b[1] / b[2], x05 = (qlogis(0.05) - b[1]) / b[2],
                                 converged = g$converged))
}
write_table(fits, "ref_psychometric_glm.csv")
cat("wrote references to", out, "\n")
