import pendula
def test_import():
    assert pendula.ellipk(0.0) == 1.5707963267948966
