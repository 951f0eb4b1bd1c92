boring(ironing).
