# The README's ParaView recipe on the last frame of spheres.pvd: Glyph,
# Sphere, scaled by `radius` (factor 2), Glyph Mode = All Points. Prints the
# number of spheres, the glyphs drawn with the recipe and with ParaView's
# default glyph mode, and the arrays ParaView sees at the first time.
import sys
from paraview.simple import *
pvd, png = sys.argv[1], sys.argv[2]
r = PVDReader(FileName=pvd)
times = r.TimestepValues
r.UpdatePipeline(time=times[0])
print("first_arrays", ",".join(sorted(r.PointData.keys())))
t = times[-1]
r.UpdatePipeline(time=t)
n = r.GetDataInformation().GetNumberOfPoints()
def glyphs(mode):
    g = Glyph(Input=r, GlyphType="Sphere")
    g.ScaleArray = ["POINTS", "radius"]
    g.ScaleFactor = 2.0
    if mode:
        g.GlyphMode = mode
    g.UpdatePipeline(time=t)
    per = g.GlyphType.ThetaResolution * (g.GlyphType.PhiResolution - 2) + 2
    return g, g.GetDataInformation().GetNumberOfPoints() // per
g, all_points = glyphs("All Points")
_, default = glyphs(None)
view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [640, 480]
Show(g, view)
view.ViewTime = t
ResetCamera(view)
Render(view)
SaveScreenshot(png, view)
print("spheres", n)
print("glyphs_all_points", all_points)
print("glyphs_default", default)
