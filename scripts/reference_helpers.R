# Shared by the scripts/make_reference_*.R scripts (sourced; run them from the repository root).
# fmt: 17 significant digits, NA as an empty cell (the C++ tests read it as NaN).
fmt <- function(x) ifelse(is.na(x), "", trimws(formatC(x, digits = 17, format = "g")))
# write_table: a data frame as CSV under `out` (a global of the calling script), numbers through fmt.
write_table <- function(df, file) {
  for (n in names(df)) if (is.numeric(df[[n]])) df[[n]] <- fmt(df[[n]])
  write.csv(df, file.path(out, file), row.names = FALSE, quote = FALSE)
}
