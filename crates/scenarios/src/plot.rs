//! Figures as PNG and SVG: line panels (orbits, time series) and histograms.
