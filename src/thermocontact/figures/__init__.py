"""The paper's Figures 2-5 and their extensions."""
