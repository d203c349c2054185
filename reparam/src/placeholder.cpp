namespace uniparam {}
