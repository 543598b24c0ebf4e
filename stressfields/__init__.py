"""stressfields: reference datasets of contact-mechanics fields."""
__version__ = "0.1.0"
