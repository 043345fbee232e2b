"""The docs' generated sections (docgen, scripts/gen_docs.py) and their data: the RTL module table
(rtl_modules), the noise units' table (noise_units), the multipass study (multipass_doc), and
the check that no figure is typed by hand (handfigures)."""
