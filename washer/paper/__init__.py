"""Reproduction of the paper's section 3 (Figs 3-11): runs, measurements, figures, report.

Data flows runs -> analysis -> figures -> report; `python -m washer.paper`
drives it.
"""
