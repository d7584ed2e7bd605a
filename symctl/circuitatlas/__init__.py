"""The circuit atlas: every minimal circuit of a controller, found, proved and ranked.

Data flows pattern -> rank -> fibre -> screen -> universality -> circuitclass -> search -> atlas.
"""
