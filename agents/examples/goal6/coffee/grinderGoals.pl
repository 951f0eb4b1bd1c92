served.
