"""Figures 10 and 11 of the paper (figdata: regress.json and labels; images: OpenImageIO images and
canvases; fig10, fig11), the flicker tables and plots of `pst animate` runs (flicker) and the
filter options' ground-truth table (fidelity)."""
