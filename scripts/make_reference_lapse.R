#!/usr/bin/env Rscript
# Reference fits of the symmetric-lapse psychometric function (issue 20) for tests/analysis/.
# Run from the repository root:   Rscript scripts/make_reference_lapse.R [OUT_DIR]
# Needs only Debian's r-base-core. crowdlab never depends on R: the outputs are committed.
#
# Model: P(yes | x) = lambda + (1 - 2 lambda) plogis(a + b x), 0 <= lambda < 0.5, maximum likelihood.
# R fits it with nlminb (PORT, bound-constrained quasi-Newton) on the standardised x, with the analytic
# gradient, from several starts, keeping the lowest negative log-likelihood; an estimate on the bound
# lambda = 0 is the plain glm(binomial) fit. The deviance check is computed over the distinct x levels.
# Outputs:
#   lapse_trials.csv      simulated answers: subject, condition, distance, collision
#   ref_lapse_fits.csv    per subject x condition: intercept, slope, lambda, x50, x05, nll, deviance,
#                         deviance_df, deviance_p
args <- commandArgs(trailingOnly = TRUE)
out <- if (length(args) > 0) args[1] else "tests/data/analysis"
source("scripts/reference_helpers.R")

set.seed(20)
levels_x <- seq(0.1, 0.9, by = 0.1)
true_lapse <- c(0, 0.02, 0.05, 0.1, 0.15, 0)
trials <- NULL
for (s in 1:6) for (cond in c("a", "b")) {
  thr <- 0.45 + ifelse(cond == "b", 0.08, 0) + rnorm(1, 0, 0.03)
  slope <- 18 + rnorm(1, 0, 3)
  lam <- true_lapse[s]
  for (x in levels_x) for (r in 1:15) {
    p <- lam + (1 - 2 * lam) * plogis(-slope * (x - thr))
    trials <- rbind(trials, data.frame(subject = s, condition = cond, distance = x, collision = rbinom(1, 1, p)))
  }
}
# One overdispersed observer: the threshold jumps between blocks (a non-stationary observer).
for (x in levels_x) for (r in 1:15) {
  thr <- if (r <= 7) 0.25 else 0.7
  trials <- rbind(trials, data.frame(subject = 7, condition = "a", distance = x,
                                     collision = rbinom(1, 1, plogis(-60 * (x - thr)))))
}
write.csv(trials, file.path(out, "lapse_trials.csv"), row.names = FALSE, quote = FALSE)

nll_fun <- function(th, z, y) {
  p <- th[3] + (1 - 2 * th[3]) * plogis(th[1] + th[2] * z)
  -sum(dbinom(y, 1, p, log = TRUE))
}
grad_fun <- function(th, z, y) {
  f <- plogis(th[1] + th[2] * z)
  p <- th[3] + (1 - 2 * th[3]) * f
  dl <- ifelse(y > 0, -1 / p, 1 / (1 - p))
  du <- (1 - 2 * th[3]) * f * (1 - f)
  c(sum(dl * du), sum(dl * du * z), sum(dl * (1 - 2 * f)))
}

fits <- NULL
for (key in unique(paste(trials$subject, trials$condition))) {
  d <- trials[paste(trials$subject, trials$condition) == key, ]
  centre <- mean(d$distance); scale <- sqrt(mean((d$distance - centre)^2))
  z <- (d$distance - centre) / scale
  g <- glm(collision ~ z, family = binomial, data = data.frame(z = z, collision = d$collision),
           control = glm.control(epsilon = 1e-14, maxit = 100))
  best <- NULL
  for (l0 in c(0.001, 0.01, 0.05, 0.1, 0.2)) {
    r <- nlminb(c(coef(g), l0), nll_fun, grad_fun, z = z, y = d$collision,
                lower = c(-Inf, -1e3, 0), upper = c(Inf, 1e3, 0.5 - 1e-6),
                control = list(rel.tol = 1e-15, x.tol = 1e-12, eval.max = 5000, iter.max = 5000))
    if (is.null(best) || r$objective < best$objective) best <- r
  }
  th <- best$par
  if (th[3] < 1e-10) { th <- c(coef(g), 0) }  # the boundary: the plain logistic fit
  a <- th[1] - th[2] * centre / scale; b <- th[2] / scale
  nll <- nll_fun(th, z, d$collision)
  # Deviance over the distinct levels against the saturated model.
  k <- tapply(d$collision, d$distance, sum); n <- tapply(d$collision, d$distance, length)
  xs <- as.numeric(names(k))
  p <- th[3] + (1 - 2 * th[3]) * plogis(a + b * xs)
  term <- function(k, m) ifelse(k > 0, k * log(k / m), 0)
  dev <- 2 * sum(term(k, n * p) + term(n - k, n * (1 - p)))
  df <- length(xs) - 3
  parts <- strsplit(key, " ")[[1]]
  fits <- rbind(fits, data.frame(subject = parts[1], condition = parts[2], intercept = a, slope = b,
                                 lambda = th[3], x50 = -a / b, x05 = (qlogis(0.05) - a) / b, nll = nll,
                                 deviance = dev, deviance_df = df,
                                 deviance_p = pchisq(dev, df, lower.tail = FALSE)))
}
write_table(fits, "ref_lapse_fits.csv")
cat("wrote lapse references to", out, "\n")
