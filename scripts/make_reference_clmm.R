#!/usr/bin/env Rscript
# Reference cumulative link mixed models for tests/analysis/ (issue 20), fitted by ordinal::clmm
# (Laplace approximation, random intercepts). Run from the repository root:
#   Rscript scripts/make_reference_clmm.R [OUT_DIR]
# Needs Debian's r-base-core and r-cran-ordinal. Inputs written here: likert_sim.csv (30 participants,
# method baseline/ours x density low/mid/high, 3 repetitions, a 5-point rating). Output: ref_clmm.csv
# (model, quantity, name, value): thresholds, fixed effects (estimate, se), random sd, logLik, and
# `laplace_se` / `laplace_threshold_se`: the standard errors from the Hessian of the exact Laplace
# log-likelihood (below).
#
# Why a second set of SEs: clmm's own SEs (Hess = TRUE) are ordinal:::deriv12, central differences with
# an absolute step of 1e-4, of getNLA.ssr, whose inner Newton iteration (C function NRalgv3) stops
# once max|gradient| < gradTol and returns the curvature D of the iterate *before* its last step. The
# objective is therefore not smooth at the 1e-9 level (the iterate count changes between neighbouring
# parameter values), and second differences with step 1e-4 amplify that by 1e8: moving clmm's own
# optimum by 1e-6 changes its SEs by up to 1.3 % (logit model here), and the default gradTol = 1e-4
# changes them by 0.3 %. laplace_nll computes the same Laplace approximation with the conditional
# modes converged to rounding and D at the mode (the quantity clmm's Hessian approximates); it agrees
# with clmm's log-likelihood at clmm's optimum to 1e-9, is re-minimised from there, and its Hessian is
# numDeriv::hessian's Richardson extrapolation (stable to 1e-5 across steps and 1e-5 shifts).
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
# Negative Laplace log-likelihood in clmm's parameters (thresholds, beta, log sd of each random term):
# -sum log P(y | u) + |u|^2 / 2 + log det(D) / 2, D = I + Z' W Z the negative Hessian of the log
# posterior in u at the joint mode u (Z: one indicator column per level of each grouping factor, times
# its sd; W = -d2 log P / db2 per row). `groups`: a list of integer level codes, one per random term.
laplace_nll <- function(par, X, y, groups, K, link) {
  pf <- if (link == "logit") plogis else pnorm
  df <- if (link == "logit") dlogis else dnorm
  ddf <- if (link == "logit") function(t) { p <- plogis(t); p * (1 - p) * (1 - 2 * p) } else
    function(t) ifelse(is.finite(t), -t * dnorm(t), 0)
  nt <- length(groups)
  th <- c(-Inf, par[1:(K - 1)], Inf); beta <- par[K:(K - 1 + ncol(X))]; sd <- exp(tail(par, nt))
  eta <- drop(X %*% beta)
  Z <- do.call(cbind, lapply(seq_len(nt), function(t) sd[t] * outer(groups[[t]], seq_len(max(groups[[t]])), "==")))
  terms <- function(u) {
    b <- drop(Z %*% u); up <- th[y + 1] - eta - b; lo <- th[y] - eta - b
    P <- pf(up) - pf(lo); d1 <- df(up) - df(lo); d2 <- ddf(up) - ddf(lo)
    w <- -(d2 / P - (d1 / P)^2)
    list(lp = log(P), s = drop(crossprod(Z, -d1 / P)), D = diag(ncol(Z)) + crossprod(Z, w * Z))
  }
  u <- rep(0, ncol(Z))
  for (it in 1:200) {
    t <- terms(u); step <- solve(t$D, t$s - u)
    if (any(!is.finite(step))) return(Inf)
    u <- u + step
    if (max(abs(step)) < 1e-13) break
  }
  t <- terms(u)
  -(sum(t$lp) - sum(u^2) / 2 - 0.5 * c(determinant(t$D)$modulus))
}
write.csv(d[, c("participant", "method", "density", "rep", "rating")], file.path(out, "likert_sim.csv"),
          row.names = FALSE, quote = FALSE)
# likert_crossed.csv: 30 participants x 12 stimuli x method, 2 repetitions, crossed random intercepts
# (participant sd 0.8, stimulus sd 0.6).
set.seed(777)
dc <- expand.grid(rep = 1:2, stimulus = 1:12, method = c("baseline", "ours"), participant = 1:30)
bp <- rnorm(30, 0, 0.8); bs <- rnorm(12, 0, 0.6)
etac <- bp[dc$participant] + bs[dc$stimulus] + 1.0 * (dc$method == "ours")
dc$rating <- sapply(etac + rlogis(nrow(dc)), function(v) 1 + sum(v > cut))
dc$participant <- paste0("p", dc$participant); dc$stimulus <- paste0("s", dc$stimulus)
write.csv(dc[, c("participant", "stimulus", "method", "rep", "rating")], file.path(out, "likert_crossed.csv"),
          row.names = FALSE, quote = FALSE)
# "categorical": the numeric column rep as a factor (R's factor(rep); crowdlab's `categorical`), as
# `analyze report` fits its spec factors.
models <- list(list(name = "logit", formula = "rating ~ method * density + (1 | participant)", link = "logit"),
               list(name = "probit", formula = "rating ~ method + density + (1 | participant)", link = "probit"),
               list(name = "categorical", formula = "rating ~ method + rep + (1 | participant)", link = "logit",
                    factors = "rep"),
               list(name = "crossed", formula = "rating ~ method + (1 | participant) + (1 | stimulus)", link = "logit",
                    data = "likert_crossed.csv"))
rows <- NULL
add <- function(model, quantity, name, value) rows <<- rbind(rows, data.frame(model = model, quantity = quantity, name = name, value = fmt(value)))
for (m in models) {
  dd <- read.csv(file.path(out, if (is.null(m$data)) "likert_sim.csv" else m$data))
  dd$rating <- factor(dd$rating, ordered = TRUE)
  for (f in m$factors) dd[[f]] <- factor(dd[[f]])
  fit <- clmm(as.formula(m$formula), data = dd, link = m$link, Hess = TRUE,
              control = clmm.control(method = "nlminb", gradTol = 1e-10, innerCtrl = "noWarn",
                                     rel.tol = 1e-14, x.tol = 1e-12, eval.max = 5000, iter.max = 5000))
  co <- summary(fit)$coefficients
  for (t in names(fit$alpha)) { add(m$name, "threshold", t, co[t, "Estimate"]); add(m$name, "threshold_se", t, co[t, "Std. Error"]) }
  for (t in names(fit$beta)) { add(m$name, "estimate", t, co[t, "Estimate"]); add(m$name, "se", t, co[t, "Std. Error"]) }
  random <- names(VarCorr(fit))
  for (g in random) add(m$name, "sd", g, attr(VarCorr(fit)[[g]], "stddev"))
  add(m$name, "loglik", "", as.numeric(logLik(fit)))
  X <- model.matrix(as.formula(gsub("\\+ \\(1 \\| [a-z]+\\)", "", m$formula)), dd)[, -1, drop = FALSE]
  y <- as.integer(dd$rating); K <- nlevels(dd$rating)
  groups <- lapply(random, function(g) as.integer(factor(dd[[g]])))
  nll <- function(p) laplace_nll(p, X, y, groups, K, m$link)
  # clmm's optimum in (thresholds, beta, log sd): one term's fit$optRes$par is already so; with several
  # terms clmm optimises the sds themselves (its general path).
  at <- c(fit$coefficients, log(sapply(random, function(g) attr(VarCorr(fit)[[g]], "stddev"))))
  stopifnot(abs(nll(at) + as.numeric(logLik(fit))) < 1e-7)
  o <- nlminb(at, nll, control = list(rel.tol = 1e-15, x.tol = 1e-15, eval.max = 5000, iter.max = 5000))
  se <- sqrt(diag(solve(numDeriv::hessian(nll, o$par))))
  for (i in seq_along(fit$alpha)) add(m$name, "laplace_threshold_se", names(fit$alpha)[i], se[i])
  for (i in seq_along(fit$beta)) add(m$name, "laplace_se", names(fit$beta)[i], se[length(fit$alpha) + i])
}
write_table(rows, "ref_clmm.csv")
cat("wrote CLMM references to", out, "\n")
