"""Drawing: the only package that imports matplotlib."""
