"""What several studies share: XCS's parameters, the classifier-system problems and protocol,
the chapter-3 task runs, the chapter-4 exploration runs, the chapter-5 part learning runs."""
