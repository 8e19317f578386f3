"""Cable configurations of suspended robots with more than 6 cables (Merlet): valid configurations, robustness radii, safety, uncertainty."""
