# Shared by the scripts/make_reference_*.R scripts (sourced; run them from the repository root).
# fmt: 17 significant digits, NA as an empty cell (the C++ tests read it as NaN).
fmt <- function(x) ifelse(is.na(x), "", trimws(formatC(x, digits = 17, format = "g")))
# write_table: a data frame as CSV under `out` (a global of the calling script), numbers through fmt.
write_table <- function(df, file) {
  for (n in names(df)) if (is.numeric(df[[n]])) df[[n]] <- fmt(df[[n]])
  write.csv(df, file.path(out, file), row.names = FALSE, quote = FALSE)
}
# add_sphericity: Mauchly's W and p, the Greenhouse-Geisser and Huynh-Feldt epsilons and their corrected
# p values from summary(car::Anova(...), multivariate = FALSE) `s` into the rows of `res` named by
# res$effect; NA for effects without a sphericity test and everywhere when `s` is NULL (between-only).
add_sphericity <- function(res, s) {
  for (k in c("mauchly_W", "mauchly_p", "gg_eps", "hf_eps", "p_gg", "p_hf")) res[[k]] <- NA_real_
  if (is.null(s) || is.null(s$sphericity.tests) || nrow(s$sphericity.tests) == 0) return(res)
  sp <- s$sphericity.tests
  adj <- s$pval.adjustments
  for (e in rownames(sp)) {
    i <- which(res$effect == e)
    res$mauchly_W[i] <- sp[e, "Test statistic"]; res$mauchly_p[i] <- sp[e, "p-value"]
    res$gg_eps[i] <- adj[e, "GG eps"]; res$hf_eps[i] <- adj[e, "HF eps"]
    res$p_gg[i] <- adj[e, "Pr(>F[GG])"]; res$p_hf[i] <- adj[e, "Pr(>F[HF])"]
  }
  res
}
