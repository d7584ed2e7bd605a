"""Internal helpers every stage uses (checks, the safe parser, exact algebra, display); not API."""
