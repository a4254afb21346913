"""Views of a result: they draw what the analysis computed and never recompute it (docs/
DESIGN.md principle 11). report (result.json, report.md, report.html) and report_view (what
the reports show, labels and key results); plots (a case's figures) and sweep_plots (a
sweep's); style (the figures' common look and writing); pictures (off-screen 3D views)."""
