"""realization"""
