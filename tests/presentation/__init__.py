"""Layer 5, presentation: plots, blit, widgets, i18n and one test_demo_<module>.py per demo module."""
