// voxlab: the explicit list of built-in renderers, in teaching order. A new
// renderer is added here, in one line; nothing registers itself behind the
// linker's back.
#include "voxlab/renderers.h"

namespace voxlab {

const RendererRegistry& rendererRegistry() {
    static const RendererRegistry registry = [] {
        RendererRegistry r;
        r.add<SlicerRenderer>();
        r.add<MipRenderer>();
        r.add<MinipRenderer>();
        r.add<AverageRenderer>();
        r.add<FirstHitRenderer>();
        r.add<SlabMipRenderer>();
        r.add<CompositeRenderer>();
        r.add<IsoRenderer>();
        r.add<Tf2dRenderer>();
        r.add<Texslice2dRenderer>();
        r.add<Texslice3dRenderer>();
        return r;
    }();
    return registry;
}

}  // namespace voxlab
