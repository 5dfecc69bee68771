"""All plotting of washer's results: style (one place for figure styling), responses
(time responses), diagrams (bifurcation diagrams from b-files), orbits (periodic orbits
from s-files); `python -m washer.plots` draws diagrams and orbits from AUTO files."""
